// The closed-form scene of the reference integrator's GPU tests: a 20 x 20 Lambertian plane
// (y = 0, albedo kRho, specular 0) seen from straight above, rendered by the reference
// (render_offline, as `lantern render --integrator reference` runs it) at kSize x kSize.
// Noisy cases: F frames of S samples per pixel each are read back separately; per pixel the mean
// over frames and its standard error give t = (mean - expected) / se (Student t with F-1 dof).
// expect_matches asserts the image mean within 0.5% of the expected mean, every |t| < 6.5 (F = 32:
// p < 1e-6 per pixel) and fewer than 1% of pixels beyond |t| > 3.3 (p = 0.002 each); a noiseless
// pixel must match to 1e-4. render_frames asserts no NaN/Inf anywhere.
#pragma once

#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <vector>

#include "engine/scene/level.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/image/image.h"

namespace lantern::runtime {
class Device;
}

namespace lantern::test {

constexpr double kPiD = 3.14159265358979323846;
constexpr float kRho = 0.6f;
constexpr std::uint32_t kSize = 64;

// The plane and the camera at height `eye` looking straight down.
Level plane_level(float eye, float yfov);

// World point on the plane y = 0 seen through pixel (x, y) at sub-pixel offset `at` (the centre
// by default).
glm::dvec3 plane_point(const Camera& camera, std::uint32_t x, std::uint32_t y,
                       glm::vec2 at = glm::vec2(0.5f));

struct Frames {
  std::vector<runtime::ImageRGBA32F> images;
};

// `frames` still frames of `spp` samples per pixel each.
Frames render_frames(runtime::Device& device, runtime::ShaderLibrary& shaders, const Level& level,
                     std::uint32_t frames, std::uint32_t spp);

using PixelValue = std::function<double(std::uint32_t, std::uint32_t)>;
using PixelFilter = std::function<bool(std::uint32_t, std::uint32_t)>;

// The assertions of the file comment for channel 0 (the tests use grey lights and albedo), over
// the pixels `include` accepts (all without it).
void expect_matches(const Frames& frames, const PixelValue& expected,
                    const PixelFilter& include = {});

}  // namespace lantern::test
