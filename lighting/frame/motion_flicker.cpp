// motion_warp, motion_compensated_change (motion_flicker.h).
#include "lighting/frame/motion_flicker.h"

#include <fmt/format.h>

#include <array>
#include <cmath>

#include "engine/core/error.h"
#include "shared/gbuffer.h"
#include "shared/scene.h"

namespace lantern::lighting {
namespace {

bool emits(const glm::vec4& emission) {
  return emission.r > 0.0f || emission.g > 0.0f || emission.b > 0.0f;
}

void require_size(std::uint32_t w, std::uint32_t h, std::uint32_t width, std::uint32_t height,
                  const char* what) {
  if (w != width || h != height) {
    throw InputError(fmt::format("motion-compensated change: {} is {}x{}, the warp {}x{}", what, w,
                                 h, width, height));
  }
}

// The world distance from pixel (x, y)'s point to the nearest of its four neighbours' on the
// same instance (0 when none is): how far apart neighbouring texels lie on its surface.
float texel_spacing(const GBufferTexels& g, std::uint32_t x, std::uint32_t y) {
  const std::size_t i = g.index(x, y);
  float nearest = 0.0f;
  const glm::ivec2 offsets[4] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  for (const glm::ivec2 o : offsets) {
    const glm::ivec2 q = glm::ivec2(x, y) + o;
    if (q.x < 0 || q.y < 0 || q.x >= static_cast<int>(g.width) ||
        q.y >= static_cast<int>(g.height)) {
      continue;
    }
    const std::size_t j = g.index(static_cast<std::uint32_t>(q.x), static_cast<std::uint32_t>(q.y));
    if (g.ids[j].x != g.ids[i].x) continue;
    const float d = glm::length(glm::vec3(g.position[j]) - glm::vec3(g.position[i]));
    if (nearest == 0.0f || d < nearest) nearest = d;
  }
  return nearest;
}

}  // namespace

MotionWarp motion_warp(const GBufferTexels& previous, const GBufferTexels& current) {
  require_size(previous.width, previous.height, current.width, current.height,
               "the previous G-buffer");
  MotionWarp warp;
  warp.width = current.width;
  warp.height = current.height;
  const std::size_t n = std::size_t{current.width} * current.height;
  warp.source.assign(n, glm::vec2(0.0f));
  warp.valid.assign(n, 0);
  for (std::uint32_t y = 0; y < current.height; ++y) {
    for (std::uint32_t x = 0; x < current.width; ++x) {
      const std::size_t i = current.index(x, y);
      const glm::vec4 p = current.position[i];
      const std::uint32_t instance = current.ids[i].x;
      if (gpu::gbuffer_is_sky(p.w) || instance == gpu::kNoInstance || emits(current.emission[i])) {
        continue;
      }
      const glm::vec2 m(current.motion[i].z, current.motion[i].w);
      if (!std::isfinite(m.x) || !std::isfinite(m.y)) continue;
      const glm::vec2 u = glm::vec2(x, y) + m;  // prev = cur + motion, texel centres at q
      warp.source[i] = u;
      const glm::vec2 b = glm::floor(u);
      if (!(b.x >= 0.0f && b.y >= 0.0f && b.x + 1.0f <= static_cast<float>(current.width) - 1.0f &&
            b.y + 1.0f <= static_cast<float>(current.height) - 1.0f)) {
        continue;
      }
      const float reach =
          kMotionWarpDepth * p.w + kMotionWarpSpacings * texel_spacing(current, x, y);
      bool same = true;
      for (int t = 0; t < 4 && same; ++t) {
        const std::size_t q = previous.index(static_cast<std::uint32_t>(b.x) + (t & 1),
                                             static_cast<std::uint32_t>(b.y) + (t >> 1));
        same = previous.ids[q].x == instance && !emits(previous.emission[q]) &&
               glm::length(glm::vec3(previous.position[q]) - glm::vec3(p)) <= reach;
      }
      if (!same) continue;
      warp.valid[i] = 1;
      ++warp.valid_count;
    }
  }
  return warp;
}

double motion_compensated_change(const runtime::ImageRGBA32F& current,
                                 const runtime::ImageRGBA32F& previous,
                                 const runtime::ImageRGBA32F& reference, const MotionWarp& warp) {
  require_size(current.width, current.height, warp.width, warp.height, "frame t");
  require_size(previous.width, previous.height, warp.width, warp.height, "frame t-1");
  require_size(reference.width, reference.height, warp.width, warp.height, "the reference");
  double change = 0.0;
  double power = 0.0;
  for (std::size_t i = 0; i < warp.valid.size(); ++i) {
    if (!warp.valid[i]) continue;
    const glm::vec2 u = warp.source[i];
    const glm::vec2 b = glm::floor(u);
    const glm::vec2 f = u - b;
    const std::array<double, 4> weight{(1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y),
                                       (1.0 - f.x) * f.y, static_cast<double>(f.x) * f.y};
    for (int c = 0; c < 3; ++c) {
      double moved = 0.0;
      for (int t = 0; t < 4; ++t) {
        const std::size_t q = (static_cast<std::size_t>(b.y) + (t >> 1)) * warp.width +
                              static_cast<std::size_t>(b.x) + (t & 1);
        moved += weight[t] * previous.pixels[4 * q + c];
      }
      const double d = current.pixels[4 * i + c] - moved;
      change += d * d;
      const double r = reference.pixels[4 * i + c];
      power += r * r;
    }
  }
  return power > 0.0 ? change / power : 0.0;
}

}  // namespace lantern::lighting
