// Textured test content (textured_assets.h).
#include "tests/textures/textured_assets.h"

#include <cstring>
#include <fstream>

#include "runtime/image/image_encode.h"
#include "tests/level/data_uri.h"

namespace lantern::test {

std::vector<std::uint8_t> make_rgba8(
    std::uint32_t w, std::uint32_t h,
    const std::function<glm::vec4(std::uint32_t, std::uint32_t)>& f) {
  std::vector<std::uint8_t> out(4ull * w * h);
  for (std::uint32_t y = 0; y < h; ++y)
    for (std::uint32_t x = 0; x < w; ++x) {
      const glm::vec4 c = glm::clamp(f(x, y), 0.0f, 1.0f);
      for (int k = 0; k < 4; ++k)
        out[4ull * (std::size_t{y} * w + x) + static_cast<std::size_t>(k)] =
            static_cast<std::uint8_t>(std::lround(c[k] * 255.0f));
    }
  return out;
}

std::vector<std::uint8_t> png_of(std::uint32_t w, std::uint32_t h,
                                 const std::vector<std::uint8_t>& rgba8) {
  return runtime::encode_rgba8(w, h, rgba8, ".png");
}

std::int32_t add_png(Level& level, std::uint32_t w, std::uint32_t h,
                     const std::vector<std::uint8_t>& rgba8, const std::string& name) {
  ImageRef ref;
  ref.name = name;
  ref.mime_type = "image/png";
  ref.embedded = png_of(w, h, rgba8);
  level.images.push_back(std::move(ref));
  return static_cast<std::int32_t>(level.images.size() - 1);
}

nlohmann::json textured_quad_gltf(const TexturedQuadOptions& o) {
  // Buffer: positions (4 x vec3), uv0 (4 x vec2), uv1 (4 x vec2), indices (6 x u32), image.
  const float positions[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const float uv0[8] = {0, 1, 1, 1, 1, 0, 0, 0};
  const float uv1[8] = {0, 0, 2, 0, 2, 2, 0, 2};
  const std::uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
  std::vector<std::uint8_t> bin(sizeof(positions) + sizeof(uv0) + sizeof(uv1) + sizeof(indices));
  std::size_t at = 0;
  for (const auto& [data, size] :
       std::initializer_list<std::pair<const void*, std::size_t>>{{positions, sizeof(positions)},
                                                                  {uv0, sizeof(uv0)},
                                                                  {uv1, sizeof(uv1)},
                                                                  {indices, sizeof(indices)}}) {
    std::memcpy(bin.data() + at, data, size);
    at += size;
  }
  const std::size_t tangent_offset = bin.size();
  if (o.tangent) {
    for (int v = 0; v < 4; ++v) {
      const std::size_t end = bin.size();
      bin.resize(end + sizeof(glm::vec4));
      std::memcpy(bin.data() + end, &*o.tangent, sizeof(glm::vec4));
    }
  }
  const std::size_t image_offset = bin.size();
  if (o.storage == ImageStorage::BufferView) {
    bin.insert(bin.end(), o.image_bytes.begin(), o.image_bytes.end());
  }
  nlohmann::json views = {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
                          {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 32}},
                          {{"buffer", 0}, {"byteOffset", 80}, {"byteLength", 32}},
                          {{"buffer", 0}, {"byteOffset", 112}, {"byteLength", 24}}};
  if (o.tangent)
    views.push_back({{"buffer", 0}, {"byteOffset", tangent_offset}, {"byteLength", 64}});
  nlohmann::json image = {{"name", "quad_image"}};
  if (o.storage == ImageStorage::BufferView) {
    image["bufferView"] = views.size();
    views.push_back(
        {{"buffer", 0}, {"byteOffset", image_offset}, {"byteLength", o.image_bytes.size()}});
    image["mimeType"] = o.mime_type;
  } else if (o.storage == ImageStorage::DataUri) {
    image["uri"] = data_uri(o.mime_type, o.image_bytes);
  } else {
    std::ofstream(o.image_file, std::ios::binary)
        .write(reinterpret_cast<const char*>(o.image_bytes.data()),
               static_cast<std::streamsize>(o.image_bytes.size()));
    image["uri"] = o.image_file.filename().string();
  }
  nlohmann::json attributes = {{"POSITION", 0}};
  if (!o.omit_texcoords) attributes["TEXCOORD_0"] = 1;
  if (o.with_texcoord1) attributes["TEXCOORD_1"] = 2;
  if (o.tangent) attributes["TANGENT"] = 4;
  nlohmann::json base_texture = {{"index", 0}, {"texCoord", o.texcoord}};
  if (!o.texture_transform.is_null())
    base_texture["extensions"] = {{"KHR_texture_transform", o.texture_transform}};
  nlohmann::json material = {{"name", "textured"},
                             {"pbrMetallicRoughness", {{"baseColorTexture", base_texture}}}};
  if (!o.alpha_mode.empty()) material["alphaMode"] = o.alpha_mode;
  nlohmann::json texture = {{"source", 0}};
  nlohmann::json doc = {
      {"asset", {{"version", "2.0"}}},
      {"buffers",
       {{{"byteLength", bin.size()},
         {"uri", data_uri("application/octet-stream", bin)}}}},
      {"bufferViews", views},
      {"accessors",
       {{{"bufferView", 0},
         {"componentType", 5126},
         {"count", 4},
         {"type", "VEC3"},
         {"min", {0, 0, 0}},
         {"max", {1, 1, 0}}},
        {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
        {{"bufferView", 2}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
        {{"bufferView", 3}, {"componentType", 5125}, {"count", 6}, {"type", "SCALAR"}}}},
      {"images", {image}},
      {"materials", {material}},
      {"meshes",
       {{{"name", "quad"},
         {"primitives", {{{"attributes", attributes}, {"indices", 3}, {"material", 0}}}}}}},
      {"nodes", {{{"mesh", 0}, {"name", "quad"}}}},
      {"scenes", {{{"nodes", {0}}}}},
      {"scene", 0},
  };
  if (o.tangent)
    doc["accessors"].push_back(
        {{"bufferView", 4}, {"componentType", 5126}, {"count", 4}, {"type", "VEC4"}});
  if (!o.sampler.is_null()) {
    doc["samplers"] = {o.sampler};
    texture["sampler"] = 0;
  }
  doc["textures"] = {texture};
  if (!o.texture_transform.is_null()) doc["extensionsUsed"] = {"KHR_texture_transform"};
  return doc;
}

}  // namespace lantern::test
