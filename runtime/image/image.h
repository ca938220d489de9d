// A CPU-side RGBA float image: what the renderer reads back and what image I/O writes.
#pragma once

#include <cstdint>
#include <vector>

namespace lantern::runtime {

struct ImageRGBA32F {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<float> pixels;  // row-major from the top-left, 4 floats per pixel

  ImageRGBA32F() = default;
  ImageRGBA32F(std::uint32_t w, std::uint32_t h) : width(w), height(h), pixels(4ull * w * h, 0.0f) {}
  float* at(std::uint32_t x, std::uint32_t y) { return &pixels[4ull * (y * width + x)]; }
  const float* at(std::uint32_t x, std::uint32_t y) const { return &pixels[4ull * (y * width + x)]; }
  // Number of pixels with a NaN or Inf in R, G or B.
  std::size_t count_non_finite() const;
};

}  // namespace lantern::runtime
