// Level test helpers: data paths, scratch files, in-memory glTF documents.
#include "tests/level/test_files.h"

#include <cstring>
#include <fstream>

#include "tests/level/data_uri.h"
#include "tests/runtime/scratch_dir.h"

namespace lantern::test {
std::filesystem::path data_dir() {
  return LANTERN_LEVEL_TEST_DATA;
}

std::filesystem::path scratch(const std::string& name) {
  return process_scratch_dir() / name;
}

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
}

std::vector<unsigned char> triangle_buffer(const std::vector<glm::vec3>& positions,
                                           const std::vector<std::uint32_t>& indices) {
  std::vector<unsigned char> bytes(positions.size() * 12 + indices.size() * 4);
  std::memcpy(bytes.data(), positions.data(), positions.size() * 12);
  std::memcpy(bytes.data() + positions.size() * 12, indices.data(), indices.size() * 4);
  return bytes;
}

void write_glb(const std::filesystem::path& path, const nlohmann::json& document,
               const std::vector<unsigned char>& bin) {
  std::string json = document.dump();
  while (json.size() % 4) json += ' ';
  std::vector<unsigned char> data = bin;
  while (data.size() % 4) data.push_back(0);
  auto u32 = [](std::string& out, std::uint32_t v) {
    out.append(reinterpret_cast<const char*>(&v), 4);
  };
  std::string out = "glTF";
  u32(out, 2);
  u32(out, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + data.size()));
  u32(out, static_cast<std::uint32_t>(json.size()));
  out += "JSON" + json;
  u32(out, static_cast<std::uint32_t>(data.size()));
  out += std::string("BIN\0", 4);
  out.append(reinterpret_cast<const char*>(data.data()), data.size());
  write_text(path, out);
}

nlohmann::json triangle_gltf(const std::vector<glm::vec3>& positions,
                             const std::vector<std::uint32_t>& indices) {
  const std::vector<unsigned char> bytes = triangle_buffer(positions, indices);
  const auto pos_bytes = positions.size() * 12;
  return {
      {"asset", {{"version", "2.0"}}},
      {"buffers",
       {{{"byteLength", bytes.size()},
         {"uri", data_uri("application/octet-stream", bytes)}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", pos_bytes}},
        {{"buffer", 0}, {"byteOffset", pos_bytes}, {"byteLength", indices.size() * 4}}}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", positions.size()}, {"type", "VEC3"}},
        {{"bufferView", 1},
         {"componentType", 5125},
         {"count", indices.size()},
         {"type", "SCALAR"}}}},
      {"materials", {{{"name", "m"}}}},
      {"meshes",
       {{{"name", "tri"},
         {"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"material", 0}}}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"scenes", {{{"nodes", {0}}}}},
      {"scene", 0},
  };
}

}  // namespace lantern::test
