// Reading glTF accessors into typed arrays with bounds and type checks (tinygltf does not check
// that an accessor fits its buffer). Errors name the file and the accessor index.
#pragma once

#include <tiny_gltf.h>

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace lantern {

class GltfAccessorReader {
 public:
  // `where` prefixes error messages (the file name).
  GltfAccessorReader(const tinygltf::Model& model, std::string where)
      : model_(model), where_(std::move(where)) {}

  // Float scalars/vectors; `allow_normalized` also accepts normalized u8/u16 (texcoords,
  // rotations).
  std::vector<float> scalars(int accessor, bool allow_normalized = false) const;
  std::vector<glm::vec2> vec2s(int accessor, bool allow_normalized = false) const;
  std::vector<glm::vec3> vec3s(int accessor) const;
  std::vector<glm::vec4> vec4s(int accessor, bool allow_normalized = false) const;
  std::vector<std::uint32_t> indices(int accessor) const;

  [[noreturn]] void fail(int accessor, const std::string& message) const;

 private:
  // Each element's components as floats; checks type, bounds and stride.
  std::vector<float> read(int accessor, int components, bool allow_normalized) const;
  const tinygltf::Accessor& accessor_at(int accessor) const;

  const tinygltf::Model& model_;
  std::string where_;
};

}  // namespace lantern
