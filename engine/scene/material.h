// Materials (glTF metallic-roughness + KHR_materials_emissive_strength + KHR_materials_specular)
// and the images they reference. Pixels are not loaded here: lighting/textures decodes them.
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

// glTF sampler wrap mode and filters (the sampler a texture names; defaults when it names none).
enum class TextureWrap : std::uint8_t { Repeat, ClampToEdge, MirroredRepeat };

struct TextureSampler {
  TextureWrap wrap_s = TextureWrap::Repeat;
  TextureWrap wrap_t = TextureWrap::Repeat;
  bool mag_linear = true;  // glTF magFilter NEAREST (9728) -> false
  bool min_linear = true;  // minFilter NEAREST* -> false
  bool mipmaps = true;     // minFilter NEAREST or LINEAR (no mipmap) -> false
  bool mip_linear = true;  // minFilter *_MIPMAP_NEAREST -> false
  bool operator==(const TextureSampler&) const = default;
};

// A texture slot: an index into Level::images (-1 = none), the UV set it uses, its sampler and
// its KHR_texture_transform (uv' = T * R * S * uv, glTF's order; rotation counter-clockwise in
// uv space, radians).
struct TextureRef {
  std::int32_t image = -1;
  std::uint32_t texcoord = 0;
  TextureSampler sampler;
  glm::vec2 offset{0.0f};
  float rotation = 0.0f;
  glm::vec2 scale{1.0f};
  bool present() const { return image >= 0; }
  bool operator==(const TextureRef&) const = default;
};

// glTF alphaMode. Blend is rendered as Mask at cutoff 0.5 (the importer warns once per file).
enum class AlphaMode : std::uint8_t { Opaque, Mask, Blend };

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
  AlphaMode alpha_mode = AlphaMode::Opaque;
  float alpha_cutoff = 0.5f;  // Mask: a point with alpha below this is not there
  float normal_scale = 1.0f;  // normalTexture.scale
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
  // Alpha cutout in effect (Mask, or Blend rendered as Mask).
  bool alpha_tested() const { return alpha_mode != AlphaMode::Opaque; }
  bool textured() const {
    return base_color_texture.present() || metallic_roughness_texture.present() ||
           normal_texture.present() || emissive_texture.present();
  }
};

}  // namespace lantern
