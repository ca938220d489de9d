// Dynamic resolution for `lantern play`: holds a frame-time target by moving the internal
// (render) size between a floor and the window size. Frame cost on the lighting passes grows with
// the pixel count, so the next scale is the current one times sqrt(target / measured), applied
// only outside a +-10% dead band and at most every kSettleFrames frames (a size change drops the
// temporal history: ReSTIR's reservoirs, the denoiser's and the upscaler's). No GPU, no window:
// unit-tested on its own (tests/play/play_cpu_test.cpp).
#pragma once

#include <cstdint>
#include <utility>

namespace lantern::app {

struct DynamicResolutionConfig {
  double target_ms = 33.0;  // frame-time target; 0 turns dynamic resolution off (scale 1)
  float min_scale = 0.25f;  // floor of internal / window size, per axis
};

class DynamicResolution {
 public:
  static constexpr int kSettleFrames = 4;   // frames between changes (history to rebuild)
  static constexpr double kDeadBand = 0.1;  // no change while within +-10% of the target
  static constexpr std::uint32_t kMinPixels = 16;  // per axis, whatever min_scale says

  explicit DynamicResolution(const DynamicResolutionConfig& config);

  // Feeds one frame's time (ms); returns the scale for the next frame.
  float update(double frame_ms);
  // The internal size for a window of `width` x `height` at the current scale, within
  // [floor, window] per axis.
  std::pair<std::uint32_t, std::uint32_t> internal_size(std::uint32_t width,
                                                        std::uint32_t height) const;
  float scale() const { return scale_; }
  double smoothed_ms() const { return smoothed_ms_; }
  const DynamicResolutionConfig& config() const { return config_; }

 private:
  DynamicResolutionConfig config_;
  float scale_ = 1.0f;
  double smoothed_ms_ = 0.0;
  int since_change_ = 0;
};

}  // namespace lantern::app
