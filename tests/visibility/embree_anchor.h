// The physical-limit anchor of visibility_bench: Intel Embree 3 (libembree-dev, which the host
// visibility backend links too) tracing the bench's own rays with single-ray
// queries (rtcIntersect1 / rtcOccluded1) on a fixed number of host threads, over the level's
// triangles in one of two layouts:
//   flat:      one scene over every instance's world-space triangles (Embree builds one BVH);
//   two-level: one scene per mesh (object space) placed by instance geometries, as SceneBvh does.
// Answers in the probe's format (tests/visibility/visibility_harness.h cpu_probe): mode 0 closest
// hit (instance, primitive, t bits, 0) or ~0u, mode 1 w = 1 when the segment origin ->
// origin + direction is unblocked, with the one shadow-epsilon policy of shared/bvh.h.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/scene/level.h"
#include "shared/bvh.h"

namespace lantern::lighting::test {

enum class EmbreeLayout { Flat, TwoLevel };

std::string_view embree_layout_name(EmbreeLayout layout);

class EmbreeAnchor {
 public:
  // Builds the scene of `level` (all instances, same order and triangle ids as build_scene_data's
  // SceneBvh). Throws std::runtime_error when Embree fails (naming its error).
  EmbreeAnchor(const Level& level, EmbreeLayout layout, unsigned threads);
  ~EmbreeAnchor();
  EmbreeAnchor(const EmbreeAnchor&) = delete;
  EmbreeAnchor& operator=(const EmbreeAnchor&) = delete;

  // Traces `rays` (mode 0 closest hit, 1 shadow segment) on the anchor's threads (rays dealt in
  // chunks of 64 from a shared counter); sets *wall_ms to the wall time of the tracing, thread
  // start and join included (tens of microseconds), when given.
  std::vector<glm::uvec4> run(std::span<const gpu::BvhRay> rays, std::uint32_t mode,
                              double* wall_ms = nullptr) const;

  double build_ms() const { return build_ms_; }
  EmbreeLayout layout() const { return layout_; }
  const std::string& version() const { return version_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  EmbreeLayout layout_;
  double build_ms_ = 0.0;
  std::string version_;
};

// Fraction of rays on which two probe-format answers agree: mode 0 hit or miss, mode 1 visible or
// blocked.
double probe_agreement(std::span<const glm::uvec4> a, std::span<const glm::uvec4> b,
                       std::uint32_t mode);

}  // namespace lantern::lighting::test
