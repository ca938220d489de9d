// Error metrics between a rendered image and a reference: what bias tests, `lantern trade` and
// equal-time comparisons report. RGB only (alpha ignored); images must have the same size.
#pragma once

#include <cstdint>
#include <vector>

#include "runtime/image/image.h"

namespace lantern::runtime {

// Relative mean squared error: mean over pixels and RGB channels of (x - r)^2 / (r^2 + epsilon).
// epsilon keeps near-black reference pixels from dominating (0.01 is the common choice).
// Throws lantern::InputError on a size mismatch.
double relative_mse(const ImageRGBA32F& image, const ImageRGBA32F& reference,
                    double epsilon = 0.01);

// Same, restricted to the pixels where mask[y * width + x] != 0 (0 when the mask selects none).
double relative_mse(const ImageRGBA32F& image, const ImageRGBA32F& reference,
                    const std::vector<std::uint8_t>& mask, double epsilon = 0.01);

// Mean of the RGB channels over all pixels (the "overall mean" of bias tests).
double mean_rgb(const ImageRGBA32F& image);

// The relative_mse an image is expected to have against its own expectation when each of its
// pixels carries the given standard error (per RGB channel): mean over pixels and RGB of
// se^2 / (image^2 + epsilon). For a reference made by averaging frames (ImageAccumulator) this is
// its own noise, which every relMSE measured against it carries (no less: with standard errors
// from the frames' spread it is an underestimate where a heavy tail's rare values never came
// up). Throws InputError on a size mismatch.
double relative_mse_of_noise(const ImageRGBA32F& image, const ImageRGBA32F& standard_error,
                             double epsilon = 0.01);

// Mean of many frames, pixel by pixel, accumulated in double precision, and the standard error
// of that mean from the frames' spread.
class ImageAccumulator {
 public:
  void add(const ImageRGBA32F& image);
  ImageRGBA32F mean() const;
  // Per pixel and RGB channel sqrt(s^2 / count), s^2 the frames' sample variance (alpha 1);
  // needs at least 2 frames (InputError otherwise). Where a heavy-tailed integrand's rare large
  // values never came up it is an underestimate.
  ImageRGBA32F standard_error() const;
  std::uint32_t count() const { return count_; }

 private:
  std::uint32_t width_ = 0;
  std::uint32_t height_ = 0;
  std::uint32_t count_ = 0;
  std::vector<double> sum_;
  std::vector<double> sum_squares_;
};

}  // namespace lantern::runtime
