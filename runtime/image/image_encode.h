// Encodes 8-bit RGBA images (PNG, JPEG) or float RGBA (EXR) into file bytes in memory through
// OpenImageIO, as stored: no tonemap, no colour conversion (image_io.h's write_png tonemaps
// radiance; this writes texture content). Used to generate textured assets at load time and by
// tests. lantern::RuntimeError when OpenImageIO fails.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace lantern::runtime {

// `extension`: ".png" or ".jpg" (rgba8: 4 bytes per texel, row-major from the top-left).
std::vector<std::uint8_t> encode_rgba8(std::uint32_t width, std::uint32_t height,
                                       std::span<const std::uint8_t> rgba8,
                                       const std::string& extension = ".png");
// EXR, half float RGBA.
std::vector<std::uint8_t> encode_exr(std::uint32_t width, std::uint32_t height,
                                     std::span<const float> rgba);

}  // namespace lantern::runtime
