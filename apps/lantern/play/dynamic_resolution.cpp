// DynamicResolution (dynamic_resolution.h).
#include "apps/lantern/play/dynamic_resolution.h"

#include <algorithm>
#include <cmath>

namespace lantern::app {

DynamicResolution::DynamicResolution(const DynamicResolutionConfig& config) : config_(config) {
  config_.min_scale = std::clamp(config_.min_scale, 0.01f, 1.0f);
}

float DynamicResolution::update(double frame_ms) {
  if (config_.target_ms <= 0.0 || !(frame_ms > 0.0) || !std::isfinite(frame_ms)) return scale_;
  // Smooth over a few frames; restart after a change (the old size's times say nothing).
  smoothed_ms_ = since_change_ == 0 ? frame_ms : 0.7 * smoothed_ms_ + 0.3 * frame_ms;
  if (++since_change_ < kSettleFrames) return scale_;
  const double ratio = smoothed_ms_ / config_.target_ms;
  if (std::abs(ratio - 1.0) <= kDeadBand) return scale_;
  const float next = std::clamp(static_cast<float>(scale_ / std::sqrt(ratio)), config_.min_scale,
                                1.0f);
  if (std::abs(next - scale_) < 0.02f * scale_) return scale_;  // pinned at a limit
  scale_ = next;
  since_change_ = 0;
  return scale_;
}

std::pair<std::uint32_t, std::uint32_t> DynamicResolution::internal_size(
    std::uint32_t width, std::uint32_t height) const {
  auto axis = [&](std::uint32_t size) {
    const auto scaled = static_cast<std::uint32_t>(std::lround(scale_ * static_cast<float>(size)));
    const auto floor = std::max(
        std::min(size, kMinPixels),
        static_cast<std::uint32_t>(std::ceil(config_.min_scale * static_cast<float>(size))));
    return std::clamp(scaled, floor, size);
  };
  return {axis(width), axis(height)};
}

}  // namespace lantern::app
