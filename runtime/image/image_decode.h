// Decodes the images materials reference (PNG, JPEG, EXR, anything OpenImageIO reads) from a file
// or from encoded bytes embedded in a glTF file (data URI or buffer view). Values come back as
// stored (an 8-bit sRGB PNG reads as its encoded values in [0,1]); the caller decides the colour
// space by the texture's use. Bad input -- missing file, unknown or hostile bytes, truncated
// data, a side beyond `max_side` -- is one lantern::InputError naming the image and the problem.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace lantern::runtime {

struct DecodedImage {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  bool high_dynamic_range = false;  // stored as float/half (EXR, HDR): keep it in half texels
  std::vector<float> rgba;          // row-major from the top-left, 4 floats per texel

  const float* at(std::uint32_t x, std::uint32_t y) const {
    return &rgba[4ull * (std::uint64_t{y} * width + x)];
  }
};

// `where` names the image in errors (e.g. "level.gltf: image 2 'sign'").
DecodedImage decode_image_file(const std::filesystem::path& path, std::uint32_t max_side,
                               const std::string& where);
// `mime_type` may be empty: the format is then told from the bytes' signature.
DecodedImage decode_image_bytes(std::span<const std::uint8_t> bytes, const std::string& mime_type,
                                std::uint32_t max_side, const std::string& where);

}  // namespace lantern::runtime
