// Textured test content built in memory: 8-bit images encoded as PNG (runtime/image/
// image_encode.h), a textured quad as a glTF document (TEXCOORD_0/1, image by data URI or buffer
// view, sampler, KHR_texture_transform, TANGENT) and Level helpers that attach an embedded image to a
// material slot.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "engine/scene/level.h"

namespace lantern::test {

// rgba8 texels of a w x h image from f(x, y) -> RGBA in [0, 1] (encoded values, as stored).
std::vector<std::uint8_t> make_rgba8(
    std::uint32_t w, std::uint32_t h,
    const std::function<glm::vec4(std::uint32_t, std::uint32_t)>& f);
std::vector<std::uint8_t> png_of(std::uint32_t w, std::uint32_t h,
                                 const std::vector<std::uint8_t>& rgba8);

// Appends an embedded PNG to level.images; returns its index.
std::int32_t add_png(Level& level, std::uint32_t w, std::uint32_t h,
                     const std::vector<std::uint8_t>& rgba8, const std::string& name = "test");

// How a textured quad document stores its image.
enum class ImageStorage { DataUri, BufferView, File };

struct TexturedQuadOptions {
  ImageStorage storage = ImageStorage::DataUri;
  std::vector<std::uint8_t> image_bytes;  // encoded file bytes (PNG/JPEG/EXR)
  std::string mime_type = "image/png";
  std::filesystem::path image_file;  // ImageStorage::File: written here, referenced by name
  int texcoord = 0;                  // the baseColorTexture's set
  bool with_texcoord1 = false;       // the primitive also has TEXCOORD_1
  bool omit_texcoords = false;       // no TEXCOORD attribute at all
  nlohmann::json sampler;            // glTF sampler object (null: none)
  nlohmann::json texture_transform;  // KHR_texture_transform (null: none)
  std::string alpha_mode;            // "" = default
  std::optional<glm::vec4> tangent;  // a TANGENT attribute, this value at every vertex
};

// One quad (two triangles, unit square in z = 0, facing +Z) with a baseColorTexture.
nlohmann::json textured_quad_gltf(const TexturedQuadOptions& options);

}  // namespace lantern::test
