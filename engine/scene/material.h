// Materials (glTF metallic-roughness + KHR_materials_emissive_strength + KHR_materials_specular)
// and the images they reference. Pixels are not loaded here: the runtime reads them later.
#pragma once

#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace lantern {

// An image referenced by a material or the environment: a file path, or encoded bytes that were
// embedded in a glTF file (data URI or buffer view). Exactly one of the two is set.
struct ImageRef {
  std::string name;
  std::filesystem::path path;          // absolute; empty when embedded
  std::string mime_type;               // e.g. "image/png"; may be empty for files
  std::vector<std::uint8_t> embedded;  // encoded file bytes (PNG/JPEG...), when embedded
};

// A texture slot: an index into Level::images (-1 = none) and the UV set it uses.
struct TextureRef {
  std::int32_t image = -1;
  std::uint32_t texcoord = 0;
  bool present() const { return image >= 0; }
  bool operator==(const TextureRef&) const = default;
};

struct Material {
  std::string name;
  glm::vec4 base_color{1.0f};  // linear RGBA factor
  float metallic = 1.0f;       // glTF defaults
  float roughness = 1.0f;
  glm::vec3 emissive_factor{0.0f};
  float emissive_strength = 1.0f;  // KHR_materials_emissive_strength
  float specular_factor = 1.0f;    // KHR_materials_specular; 0 = pure Lambertian dielectric
  glm::vec3 specular_color{1.0f};  // KHR_materials_specular specularColorFactor
  bool double_sided = false;
  TextureRef base_color_texture;
  TextureRef metallic_roughness_texture;
  TextureRef normal_texture;
  TextureRef emissive_texture;

  // Emitted radiance in W/(sr·m²) per channel, front face (CLI.md "glTF units"), before any
  // emissive texture.
  glm::vec3 emitted_radiance() const { return emissive_factor * emissive_strength; }
  bool emissive() const {
    glm::vec3 l = emitted_radiance();
    return l.x > 0.0f || l.y > 0.0f || l.z > 0.0f;
  }
};

}  // namespace lantern
