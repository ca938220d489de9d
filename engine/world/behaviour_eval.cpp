// Behaviour evaluation (see behaviour_eval.h).
#include "engine/world/behaviour_eval.h"

#include <algorithm>
#include <cmath>

#include "engine/core/rng.h"

namespace lantern {

glm::quat rotate_at(const RotateBehaviour& b, const glm::quat& base, double t) {
  const auto angle =
      static_cast<float>(std::fmod(static_cast<double>(b.speed) * t, 2.0 * glm::pi<double>()));
  return glm::normalize(base * glm::angleAxis(angle, glm::normalize(b.axis)));
}

glm::vec3 orbit_at(const OrbitBehaviour& b, double t) {
  const glm::vec3 axis = glm::normalize(b.axis);
  const glm::vec3 ref =
      std::abs(axis.x) > 0.9f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
  const glm::vec3 u = glm::normalize(ref - axis * glm::dot(ref, axis));
  const double angle = std::fmod(static_cast<double>(b.phase) + static_cast<double>(b.speed) * t,
                                 2.0 * glm::pi<double>());
  return b.center + b.radius * (glm::angleAxis(static_cast<float>(angle), axis) * u);
}

float flicker_at(const FlickerBehaviour& b, std::uint64_t world_seed, StableId id, double t) {
  const Rng entity =
      Rng(world_seed).split((static_cast<std::uint64_t>(id.kind) << 32u) | id.value).split(b.seed);
  const double u = std::max(0.0, t * static_cast<double>(b.rate));
  const double cell = std::floor(u);
  const auto k = static_cast<std::uint64_t>(cell);
  const float v0 = entity.split(k).next_float();
  const float v1 = entity.split(k + 1).next_float();
  const auto f = static_cast<float>(u - cell);
  const float s = f * f * (3.0f - 2.0f * f);
  return b.min + (b.max - b.min) * (v0 + (v1 - v0) * s);
}

float follow_path_time(const FollowPathBehaviour& b, const CameraPath& path, double t) {
  double local = static_cast<double>(b.speed) * t;
  const double duration = path.duration();
  if (b.loop && duration > 0.0) {
    local = std::fmod(local, duration);
    if (local < 0.0) local += duration;
  }
  return static_cast<float>(static_cast<double>(path.start_time()) + local);
}

}  // namespace lantern
