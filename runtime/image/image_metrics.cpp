#include "runtime/image/image_metrics.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "engine/core/error.h"

namespace lantern::runtime {
namespace {

void require_same_size(const ImageRGBA32F& a, const ImageRGBA32F& b) {
  if (a.width != b.width || a.height != b.height) {
    throw InputError(fmt::format("image is {}x{} but the reference is {}x{}", a.width, a.height,
                                 b.width, b.height));
  }
}

double pixel_relative_se(const float* x, const float* r, double epsilon) {
  double sum = 0.0;
  for (int c = 0; c < 3; ++c) {
    const double d = static_cast<double>(x[c]) - static_cast<double>(r[c]);
    sum += d * d / (static_cast<double>(r[c]) * r[c] + epsilon);
  }
  return sum / 3.0;
}

}  // namespace

double relative_mse(const ImageRGBA32F& image, const ImageRGBA32F& reference, double epsilon) {
  require_same_size(image, reference);
  const std::size_t n = std::size_t{image.width} * image.height;
  if (n == 0) return 0.0;
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    sum += pixel_relative_se(&image.pixels[4 * i], &reference.pixels[4 * i], epsilon);
  }
  return sum / static_cast<double>(n);
}

double relative_mse(const ImageRGBA32F& image, const ImageRGBA32F& reference,
                    const std::vector<std::uint8_t>& mask, double epsilon) {
  require_same_size(image, reference);
  const std::size_t n = std::size_t{image.width} * image.height;
  if (mask.size() != n) {
    throw InputError(fmt::format("mask has {} entries for {} pixels", mask.size(), n));
  }
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!mask[i]) continue;
    sum += pixel_relative_se(&image.pixels[4 * i], &reference.pixels[4 * i], epsilon);
    ++count;
  }
  return count ? sum / static_cast<double>(count) : 0.0;
}

double mean_rgb(const ImageRGBA32F& image) {
  const std::size_t n = std::size_t{image.width} * image.height;
  if (n == 0) return 0.0;
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    sum += static_cast<double>(image.pixels[4 * i]) + image.pixels[4 * i + 1] +
           image.pixels[4 * i + 2];
  }
  return sum / (3.0 * static_cast<double>(n));
}

double relative_mse_of_noise(const ImageRGBA32F& image, const ImageRGBA32F& standard_error,
                             double epsilon) {
  require_same_size(standard_error, image);
  const std::size_t n = std::size_t{image.width} * image.height;
  if (n == 0) return 0.0;
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) {
      const double se = standard_error.pixels[4 * i + c];
      const double x = image.pixels[4 * i + c];
      sum += se * se / (x * x + epsilon);
    }
  }
  return sum / (3.0 * static_cast<double>(n));
}

void ImageAccumulator::add(const ImageRGBA32F& image) {
  if (count_ == 0) {
    width_ = image.width;
    height_ = image.height;
    sum_.assign(image.pixels.size(), 0.0);
    sum_squares_.assign(image.pixels.size(), 0.0);
  } else if (image.width != width_ || image.height != height_) {
    throw InputError(fmt::format("accumulating a {}x{} image into a {}x{} mean", image.width,
                                 image.height, width_, height_));
  }
  for (std::size_t i = 0; i < sum_.size(); ++i) {
    const double x = image.pixels[i];
    sum_[i] += x;
    sum_squares_[i] += x * x;
  }
  ++count_;
}

ImageRGBA32F ImageAccumulator::standard_error() const {
  if (count_ < 2) {
    throw InputError(fmt::format("a standard error needs at least 2 frames, not {}", count_));
  }
  ImageRGBA32F out(width_, height_);
  const double n = count_;
  for (std::size_t i = 0; i < sum_.size(); ++i) {
    if (i % 4 == 3) {
      out.pixels[i] = 1.0f;
      continue;
    }
    const double mean = sum_[i] / n;
    const double variance = std::max((sum_squares_[i] - n * mean * mean) / (n - 1.0), 0.0);
    out.pixels[i] = static_cast<float>(std::sqrt(variance / n));
  }
  return out;
}

ImageRGBA32F ImageAccumulator::mean() const {
  ImageRGBA32F out(width_, height_);
  if (count_ == 0) return out;
  for (std::size_t i = 0; i < sum_.size(); ++i) {
    out.pixels[i] = static_cast<float>(sum_[i] / count_);
  }
  return out;
}

}  // namespace lantern::runtime
