// Motion-compensated frame-to-frame change: frame t against frame t-1 moved along the scene's own
// motion (gbuffer.motion's zw), over the pixels both frames show as the same surface. What
// `lantern trade` reports as the flicker of a moving view, where the plain frame-to-frame change
// measures the camera's motion more than the image's unsteadiness; on a still view it is that
// plain change restricted to the compared pixels.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "lighting/frame/gbuffer_readback.h"
#include "runtime/image/image.h"

namespace lantern::lighting {

// Where each pixel of frame t was in frame t-1, and whether it can be compared there.
struct MotionWarp {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  // Per pixel: the point's position in frame t-1 in texel coordinates (texel q's centre at q).
  std::vector<glm::vec2> source;
  // Per pixel: 1 where frame t shows a surface that is no emitter (the denoiser passes emitters
  // through) and frame t-1's four texels around `source` show the same instance, no emitter, and
  // points near it (kMotionWarpDepth, kMotionWarpSpacings; else a disocclusion); 0 otherwise.
  std::vector<std::uint8_t> valid;
  std::size_t valid_count = 0;
};

// A texel of frame t-1 farther from the point than kMotionWarpSpacings texel spacings (the world
// distance to the nearest of the pixel's four neighbours on its instance: how far apart texels
// lie on its surface at this size) plus kMotionWarpDepth x its view depth is another surface:
// the point was hidden there. In texel units, so an image is judged alike at every size. The
// figure a view gets depends on this choice more than one would like: a few pixels carry most of
// a moving view's change (README, "The speed/accuracy trade").
inline constexpr float kMotionWarpSpacings = 2.5f;
inline constexpr float kMotionWarpDepth = 0.01f;

// From the G-buffers of frames t-1 and t (same size). InputError on a size mismatch.
MotionWarp motion_warp(const GBufferTexels& previous, const GBufferTexels& current);

// Sum over the valid pixels and RGB of (current - previous bilinearly at `source`)^2, over the
// same sum of reference^2 (reference: frame t's reference image); 0 when no pixel is valid.
// InputError when an image's size differs from the warp's.
double motion_compensated_change(const runtime::ImageRGBA32F& current,
                                 const runtime::ImageRGBA32F& previous,
                                 const runtime::ImageRGBA32F& reference, const MotionWarp& warp);

}  // namespace lantern::lighting
