// glTF accessor reading with validation.
#include "engine/level/gltf_accessor.h"

#include <fmt/format.h>

#include <cstring>

#include "engine/core/error.h"

namespace lantern {
namespace {

// The bytes of element `i` of an accessor whose layout has been validated.
struct Layout {
  const unsigned char* base = nullptr;
  std::size_t stride = 0;
  std::size_t component_size = 0;
};

float component(const unsigned char* p, int type, bool normalized) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float f;
      std::memcpy(&f, p, 4);
      return f;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalized ? static_cast<float>(*p) / 255.0f : static_cast<float>(*p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? static_cast<float>(v) / 65535.0f : static_cast<float>(v);
    }
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      std::int8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? std::max(static_cast<float>(v) / 127.0f, -1.0f) : static_cast<float>(v);
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      std::int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(static_cast<float>(v) / 32767.0f, -1.0f) : static_cast<float>(v);
    }
    default:
      return 0.0f;
  }
}

// Whether `count` elements of `element` bytes, `stride` apart, starting at `offset` of a buffer
// view of `view_length` bytes that starts at `view_offset` of a buffer of `buffer_size` bytes, all
// fit. Written with subtractions and a division only: every size comes from the file (no overflow).
bool elements_fit(std::size_t count, std::size_t stride, std::size_t element, std::size_t offset,
                  std::size_t view_offset, std::size_t view_length, std::size_t buffer_size) {
  if (view_offset > buffer_size || view_length > buffer_size - view_offset) return false;
  if (count == 0) return true;
  if (offset > view_length || element > view_length - offset) return false;
  return count - 1 <= (view_length - offset - element) / stride;
}

// Accessors without a buffer view are all zeros (glTF); their size is still the file's word.
constexpr std::size_t kMaxZeroAccessorElements = std::size_t{1} << 24;

}  // namespace

void GltfAccessorReader::fail(int accessor, const std::string& message) const {
  throw InputError(fmt::format("{}: accessor {}: {}", where_, accessor, message));
}

const tinygltf::Accessor& GltfAccessorReader::accessor_at(int accessor) const {
  if (accessor < 0 || static_cast<std::size_t>(accessor) >= model_.accessors.size())
    throw InputError(fmt::format("{}: accessor {} does not exist ({} accessors)", where_, accessor,
                                 model_.accessors.size()));
  return model_.accessors[static_cast<std::size_t>(accessor)];
}

std::vector<float> GltfAccessorReader::read(int index, int components,
                                            bool allow_normalized) const {
  const tinygltf::Accessor& a = accessor_at(index);
  if (a.sparse.isSparse) fail(index, "sparse accessors are not supported");
  const int have = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
  if (have != components)
    fail(index, fmt::format("has {} components per element, expected {}", have, components));
  const bool is_float = a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
  if (!is_float && !(allow_normalized && a.normalized))
    fail(index, fmt::format("component type {} is not supported here (float{})", a.componentType,
                            allow_normalized ? " or normalized integers" : ""));
  if (a.bufferView < 0) {  // all zeros per the glTF spec
    if (a.count > kMaxZeroAccessorElements)
      fail(index, fmt::format("{} elements without a buffer view (limit {})", a.count,
                              kMaxZeroAccessorElements));
    return std::vector<float>(a.count * static_cast<std::size_t>(components), 0.0f);
  }
  if (static_cast<std::size_t>(a.bufferView) >= model_.bufferViews.size())
    fail(index, fmt::format("buffer view {} does not exist", a.bufferView));
  const tinygltf::BufferView& view = model_.bufferViews[static_cast<std::size_t>(a.bufferView)];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model_.buffers.size())
    fail(index, fmt::format("buffer view {} names missing buffer {}", a.bufferView, view.buffer));
  const tinygltf::Buffer& buffer = model_.buffers[static_cast<std::size_t>(view.buffer)];
  const int stride_or_error = a.ByteStride(view);
  if (stride_or_error <= 0) fail(index, "invalid byte stride");
  const auto stride = static_cast<std::size_t>(stride_or_error);
  const auto csize = static_cast<std::size_t>(
      tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType)));
  const std::size_t element = csize * static_cast<std::size_t>(components);
  if (!elements_fit(a.count, stride, element, a.byteOffset, view.byteOffset, view.byteLength,
                    buffer.data.size()))
    fail(index,
         fmt::format("{} elements at offset {} overrun buffer view {} ({} bytes at {}) / buffer {} "
                     "({} bytes)",
                     a.count, a.byteOffset, a.bufferView, view.byteLength, view.byteOffset,
                     view.buffer, buffer.data.size()));
  const std::size_t start = view.byteOffset + a.byteOffset;
  std::vector<float> out(a.count * static_cast<std::size_t>(components), 0.0f);
  for (std::size_t i = 0; i < a.count; ++i) {
    const unsigned char* p = buffer.data.data() + start + i * stride;
    for (int c = 0; c < components; ++c)
      out[i * static_cast<std::size_t>(components) + static_cast<std::size_t>(c)] =
          component(p + static_cast<std::size_t>(c) * csize, a.componentType, a.normalized);
  }
  return out;
}

std::vector<float> GltfAccessorReader::scalars(int accessor, bool allow_normalized) const {
  return read(accessor, 1, allow_normalized);
}

std::vector<glm::vec2> GltfAccessorReader::vec2s(int accessor, bool allow_normalized) const {
  const std::vector<float> f = read(accessor, 2, allow_normalized);
  std::vector<glm::vec2> out(f.size() / 2);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = {f[2 * i], f[2 * i + 1]};
  return out;
}

std::vector<glm::vec3> GltfAccessorReader::vec3s(int accessor) const {
  const std::vector<float> f = read(accessor, 3, false);
  std::vector<glm::vec3> out(f.size() / 3);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = {f[3 * i], f[3 * i + 1], f[3 * i + 2]};
  return out;
}

std::vector<glm::vec4> GltfAccessorReader::vec4s(int accessor, bool allow_normalized) const {
  const std::vector<float> f = read(accessor, 4, allow_normalized);
  std::vector<glm::vec4> out(f.size() / 4);
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = {f[4 * i], f[4 * i + 1], f[4 * i + 2], f[4 * i + 3]};
  return out;
}

std::vector<std::uint32_t> GltfAccessorReader::indices(int index) const {
  const tinygltf::Accessor& a = accessor_at(index);
  if (a.sparse.isSparse) fail(index, "sparse accessors are not supported");
  if (a.type != TINYGLTF_TYPE_SCALAR) fail(index, "index accessor is not SCALAR");
  const int ct = a.componentType;
  if (ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    fail(index, fmt::format("index component type {} is not an unsigned integer", ct));
  if (a.bufferView < 0 || static_cast<std::size_t>(a.bufferView) >= model_.bufferViews.size())
    fail(index, fmt::format("index accessor has no valid buffer view ({})", a.bufferView));
  const tinygltf::BufferView& view = model_.bufferViews[static_cast<std::size_t>(a.bufferView)];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model_.buffers.size())
    fail(index, fmt::format("buffer view {} names missing buffer {}", a.bufferView, view.buffer));
  const tinygltf::Buffer& buffer = model_.buffers[static_cast<std::size_t>(view.buffer)];
  const auto csize =
      static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(ct)));
  const int stride_or_error = a.ByteStride(view);
  const std::size_t stride =
      stride_or_error > 0 ? static_cast<std::size_t>(stride_or_error) : csize;
  if (!elements_fit(a.count, stride, csize, a.byteOffset, view.byteOffset, view.byteLength,
                    buffer.data.size()))
    fail(index, fmt::format("{} indices at offset {} overrun buffer view {}", a.count, a.byteOffset,
                            a.bufferView));
  const std::size_t start = view.byteOffset + a.byteOffset;
  std::vector<std::uint32_t> out(a.count);
  for (std::size_t i = 0; i < a.count; ++i) {
    const unsigned char* p = buffer.data.data() + start + i * stride;
    std::uint32_t v = 0;
    if (csize == 1) v = *p;
    if (csize == 2) {
      std::uint16_t s;
      std::memcpy(&s, p, 2);
      v = s;
    }
    if (csize == 4) std::memcpy(&v, p, 4);
    out[i] = v;
  }
  return out;
}

}  // namespace lantern
