// Behaviours as pure functions of time (and seed): the systems apply them, tests check them.
// Time `t` is the frame's FrameTime::time; nothing accumulates from frame to frame.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/scene/behaviour.h"
#include "engine/scene/camera_path.h"
#include "engine/world/components.h"

namespace lantern {

// base · rotation of speed·t radians about the object-space axis.
glm::quat rotate_at(const RotateBehaviour& b, const glm::quat& base, double t);

// center + radius · (R(phase + speed·t about axis) · u), where u is the unit vector of world +X
// projected into the orbit plane (world +Z when the axis is near X). For axis +Y and phase 0 the
// orbit starts at center + radius·X.
glm::vec3 orbit_at(const OrbitBehaviour& b, double t);

// Flicker multiplier in [min, max]: value noise with `rate` cells a second, smoothstep between
// cell values. Cell k's value comes from Rng(seed).split(entity).split(behaviour seed).split(k):
// it depends on the world seed, the entity's stable id and the time only, never on threads or
// on which frames were simulated before.
float flicker_at(const FlickerBehaviour& b, std::uint64_t world_seed, StableId id, double t);

// The path time at world time t: start + speed·t, wrapped into the path when `loop`, clamped
// (by CameraPath::evaluate) otherwise.
float follow_path_time(const FollowPathBehaviour& b, const CameraPath& path, double t);

}  // namespace lantern
