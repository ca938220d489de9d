// Named, time-parametrised keyframe paths (camera flythroughs; objects can follow them too).
// Positions: cubic Hermite in time with centripetal Catmull-Rom tangents (C1, passes through
// every key, no cusps on uneven spacing). Rotations: squad (smooth slerp). FOV: Hermite in time.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <optional>
#include <string>
#include <vector>

namespace lantern {

struct PathKey {
  float time = 0.0f;  // seconds
  glm::vec3 position{0.0f};
  glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f};  // camera looks down local -Z
  std::optional<float> yfov;                      // radians; all keys have it or none does
};

struct PathPose {
  glm::vec3 position{0.0f};
  glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f};
  std::optional<float> yfov;
};

struct CameraPath {
  std::string name;
  std::vector<PathKey> keys;  // strictly increasing times
  // Looping paths wrap time with period duration(); their last key should repeat the first.
  bool loop = false;

  float start_time() const { return keys.empty() ? 0.0f : keys.front().time; }
  float end_time() const { return keys.empty() ? 0.0f : keys.back().time; }
  float duration() const { return end_time() - start_time(); }

  // Empty when the path is usable; otherwise what is wrong with it (the loader adds the place).
  std::string problem() const;

  // The pose at time t: clamped to [start, end], or wrapped when `loop`. Requires problem() empty.
  PathPose evaluate(float t) const;
};

}  // namespace lantern
