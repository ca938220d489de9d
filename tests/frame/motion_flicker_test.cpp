// motion_warp / motion_compensated_change (lighting/frame/motion_flicker.h) on synthetic
// G-buffers: a view panning over a wall whose image is a ramp in the wall's x. Moved back along
// the motion, frame t-1 is frame t: no change, where the plain frame-to-frame change is large;
// noise in frame t is measured exactly; emitters, other instances (a disocclusion), far points
// and sources outside the image are left out, and the pixels of a coarse image are compared too.
#include "lighting/frame/motion_flicker.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "engine/core/error.h"
#include "shared/scene.h"

namespace lantern {
namespace {

using lighting::GBufferTexels;
using lighting::MotionWarp;
using runtime::ImageRGBA32F;

constexpr std::uint32_t kW = 24, kH = 10;
constexpr float kDepth = 5.0f;
// World units a pixel spans on the wall: a 60-degree view at about 90 rows (coarser images,
// fewer rows, spread their pixels farther apart).
constexpr float kPixel = 0.01f;

// The wall seen with the camera `pan` pixels to the right: pixel x shows wall x + pan; each point
// moved by `motion` pixels since the frame before (prev = cur + motion); a pixel spans
// `pixel_size` world units.
GBufferTexels wall(float pan, glm::vec2 motion, float pixel_size = kPixel) {
  GBufferTexels g;
  g.width = kW;
  g.height = kH;
  for (std::uint32_t y = 0; y < kH; ++y) {
    for (std::uint32_t x = 0; x < kW; ++x) {
      g.position.emplace_back((static_cast<float>(x) + pan) * pixel_size,
                              static_cast<float>(y) * pixel_size, 0.0f, kDepth);
      g.emission.emplace_back(0.0f);
      g.ids.emplace_back(1u, 0u, 0u, 0u);
      g.motion.emplace_back(motion, motion);
    }
  }
  return g;
}

float ramp(float wall_x, float y) {
  return 1.0f + 0.25f * wall_x + 0.1f * y;
}

ImageRGBA32F wall_image(float pan) {
  ImageRGBA32F image(kW, kH);
  for (std::uint32_t y = 0; y < kH; ++y) {
    for (std::uint32_t x = 0; x < kW; ++x) {
      const float v = ramp(static_cast<float>(x) + pan, static_cast<float>(y));
      for (int c = 0; c < 3; ++c) image.pixels[4 * (y * kW + x) + c] = v * (1.0f + 0.5f * c);
      image.pixels[4 * (y * kW + x) + 3] = 1.0f;
    }
  }
  return image;
}

double power(const ImageRGBA32F& image, const MotionWarp& warp) {
  double p = 0.0;
  for (std::size_t i = 0; i < warp.valid.size(); ++i) {
    if (!warp.valid[i]) continue;
    for (int c = 0; c < 3; ++c) p += double{image.pixels[4 * i + c]} * image.pixels[4 * i + c];
  }
  return p;
}

TEST(MotionFlickerTest, APanMovedBackIsNoChange) {
  // Whole and fractional pans: the bilinear fetch of a ramp is exact.
  for (const float step : {1.0f, 0.5f, 2.25f}) {
    const GBufferTexels previous = wall(0.0f, glm::vec2(0.0f));
    const GBufferTexels current = wall(step, glm::vec2(step, 0.0f));
    const MotionWarp warp = lighting::motion_warp(previous, current);
    // Sources with a texel to the right and one below inside the image: x + step < kW - 1 and
    // y < kH - 1.
    const auto inside = static_cast<std::size_t>(std::ceil(kW - 1 - step));
    EXPECT_EQ(warp.valid_count, inside * (kH - 1)) << "step " << step;
    const ImageRGBA32F a = wall_image(0.0f), b = wall_image(step);
    EXPECT_LT(lighting::motion_compensated_change(b, a, b, warp), 1e-12) << "step " << step;
    // Not moved back (the plain frame-to-frame change), the pan is a change.
    GBufferTexels still = current;
    for (glm::vec4& m : still.motion) m = glm::vec4(0.0f);
    EXPECT_GT(lighting::motion_compensated_change(b, a, b, lighting::motion_warp(current, still)),
              1e-4)
        << "step " << step;
  }
}

// A coarse image (texels 6% of the view depth apart, as at 16 rows): its pixels are compared
// too, the distance test being in texel spacings (a fixed share of the depth, 5%, rejected every
// pixel whose source texels lie a texel away); a texel 4 spacings behind is another surface.
TEST(MotionFlickerTest, CoarseImagesAreComparedToo) {
  const float coarse = 0.06f * kDepth;
  GBufferTexels previous = wall(0.0f, glm::vec2(0.0f), coarse);
  const GBufferTexels current = wall(0.5f, glm::vec2(0.5f, 0.0f), coarse);
  const MotionWarp warp = lighting::motion_warp(previous, current);
  EXPECT_EQ(warp.valid_count, std::size_t{kW - 1} * (kH - 1));
  const ImageRGBA32F a = wall_image(0.0f), b = wall_image(0.5f);
  EXPECT_LT(lighting::motion_compensated_change(b, a, b, warp), 1e-12);
  previous.position[previous.index(8, 4)].z -= 4.0f * coarse;
  EXPECT_EQ(lighting::motion_warp(previous, current).valid_count, warp.valid_count - 4);
}

TEST(MotionFlickerTest, NoiseInTheNewFrameIsMeasured) {
  const GBufferTexels previous = wall(0.0f, glm::vec2(0.0f));
  const GBufferTexels current = wall(1.0f, glm::vec2(1.0f, 0.0f));
  const MotionWarp warp = lighting::motion_warp(previous, current);
  const ImageRGBA32F a = wall_image(0.0f), reference = wall_image(1.0f);
  ImageRGBA32F b = reference;
  double noise = 0.0;
  for (std::size_t i = 0; i < warp.valid.size(); ++i) {
    const float d = (i % 3 == 0) ? 0.5f : -0.25f;
    for (int c = 0; c < 3; ++c) b.pixels[4 * i + c] += d;
    if (warp.valid[i]) noise += 3.0 * d * d;
  }
  EXPECT_NEAR(lighting::motion_compensated_change(b, a, reference, warp),
              noise / power(reference, warp), 1e-9);
}

TEST(MotionFlickerTest, EmittersDisocclusionsAndOutsideAreLeftOut) {
  GBufferTexels previous = wall(0.0f, glm::vec2(0.0f));
  GBufferTexels current = wall(1.0f, glm::vec2(1.0f, 0.0f));
  const std::size_t base = lighting::motion_warp(previous, current).valid_count;
  // An emitter in frame t, an emitter at a source texel of t-1, another instance at a source
  // texel (what frame t shows was hidden behind it), a source texel 1 m behind the point.
  current.emission[current.index(5, 4)] = glm::vec4(3.0f, 3.0f, 3.0f, 0.0f);
  previous.emission[previous.index(11, 2)] = glm::vec4(1.0f, 0.0f, 0.0f, 0.0f);
  previous.ids[previous.index(15, 6)].x = 2u;
  previous.position[previous.index(19, 8)].z -= 1.0f;
  const MotionWarp warp = lighting::motion_warp(previous, current);
  EXPECT_FALSE(warp.valid[current.index(5, 4)]);
  // Each marked texel of t-1 is a source texel of the 4 pixels at (x-2..x-1, y-1..y) in frame t.
  for (const glm::uvec2 q : {glm::uvec2(11, 2), glm::uvec2(15, 6), glm::uvec2(19, 8)}) {
    for (std::uint32_t t = 0; t < 4; ++t) {
      EXPECT_FALSE(warp.valid[current.index(q.x - 2 + (t & 1), q.y - 1 + (t >> 1))])
          << "source texel (" << q.x << ", " << q.y << ")";
    }
  }
  EXPECT_EQ(warp.valid_count, base - 1 - 3 * 4);
  // The sky, no previous position, a size mismatch.
  current.position[current.index(2, 2)].w = 0.0f;
  current.ids[current.index(2, 2)].x = gpu::kNoInstance;
  current.motion[current.index(3, 3)] = glm::vec4(-1.0e6f);
  const MotionWarp later = lighting::motion_warp(previous, current);
  EXPECT_FALSE(later.valid[current.index(2, 2)]);
  EXPECT_FALSE(later.valid[current.index(3, 3)]);
  EXPECT_THROW(lighting::motion_compensated_change(ImageRGBA32F(kW - 1, kH), wall_image(0.0f),
                                                   wall_image(0.0f), later),
               InputError);
}

}  // namespace
}  // namespace lantern
