// Behaviours as data: what an instance or light does over time. Systems that run them live with
// the ECS; here they are only parameters, loaded from levels.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <variant>

namespace lantern {

// Spins about `axis` (object space, unit length) at `speed` radians per second.
struct RotateBehaviour {
  glm::vec3 axis{0.0f, 1.0f, 0.0f};
  float speed = 1.0f;
  bool operator==(const RotateBehaviour&) const = default;
};

// Circles `center` at `radius` in the plane orthogonal to `axis`, `speed` radians per second,
// starting at `phase` radians.
struct OrbitBehaviour {
  glm::vec3 center{0.0f};
  float radius = 1.0f;
  float speed = 1.0f;
  glm::vec3 axis{0.0f, 1.0f, 0.0f};
  float phase = 0.0f;
  bool operator==(const OrbitBehaviour&) const = default;
};

// Scales the emitted power by a smooth random value in [min, max] that changes `rate` times per
// second; `seed` makes each flickering thing different and every run the same.
struct FlickerBehaviour {
  float min = 0.5f;
  float max = 1.0f;
  float rate = 8.0f;
  std::uint32_t seed = 0;
  bool operator==(const FlickerBehaviour&) const = default;
};

// Moves along the named path of the level; `speed` scales path time; `loop` wraps at the end.
struct FollowPathBehaviour {
  std::string path;
  float speed = 1.0f;
  bool loop = true;
  bool operator==(const FollowPathBehaviour&) const = default;
};

using Behaviour =
    std::variant<RotateBehaviour, OrbitBehaviour, FlickerBehaviour, FollowPathBehaviour>;

// "rotate", "orbit", "flicker", "follow_path": the names the level format uses.
const char* behaviour_type_name(const Behaviour& b);

// Whether the behaviour changes its instance's transform (flicker changes only emission).
bool behaviour_moves(const Behaviour& b);

}  // namespace lantern
