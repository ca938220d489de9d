// Camera path evaluation: Hermite segments with centripetal Catmull-Rom tangents, squad rotations.
#include "engine/scene/camera_path.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#define GLM_ENABLE_EXPERIMENTAL
#include <glm/gtx/quaternion.hpp>

#include "engine/core/error.h"
#include "engine/scene/finite.h"

namespace lantern {
namespace {

// A key's neighbours, with phantom keys at the ends of open paths and wrap-around for loops.
struct Neighbours {
  glm::vec3 prev_pos, next_pos;
  float prev_time, next_time;
  glm::quat prev_rot, next_rot;
  float prev_fov, next_fov;
};

Neighbours neighbours(const CameraPath& path, std::size_t i) {
  const auto& k = path.keys;
  const std::size_t n = k.size();
  const float period = path.duration();
  const float fov = k[i].yfov.value_or(0.0f);
  Neighbours nb{};
  if (i > 0) {
    nb.prev_pos = k[i - 1].position;
    nb.prev_time = k[i - 1].time;
    nb.prev_rot = k[i - 1].orientation;
    nb.prev_fov = k[i - 1].yfov.value_or(0.0f);
  } else if (path.loop && n > 2) {
    nb.prev_pos = k[n - 2].position;
    nb.prev_time = k[n - 2].time - period;
    nb.prev_rot = k[n - 2].orientation;
    nb.prev_fov = k[n - 2].yfov.value_or(0.0f);
  } else {  // reflect the next key through this one
    nb.prev_pos = 2.0f * k[i].position - k[i + 1].position;
    nb.prev_time = 2.0f * k[i].time - k[i + 1].time;
    nb.prev_rot = k[i].orientation;
    nb.prev_fov = 2.0f * fov - k[i + 1].yfov.value_or(0.0f);
  }
  if (i + 1 < n) {
    nb.next_pos = k[i + 1].position;
    nb.next_time = k[i + 1].time;
    nb.next_rot = k[i + 1].orientation;
    nb.next_fov = k[i + 1].yfov.value_or(0.0f);
  } else if (path.loop && n > 2) {
    nb.next_pos = k[1].position;
    nb.next_time = k[1].time + period;
    nb.next_rot = k[1].orientation;
    nb.next_fov = k[1].yfov.value_or(0.0f);
  } else {
    nb.next_pos = 2.0f * k[i].position - k[i - 1].position;
    nb.next_time = 2.0f * k[i].time - k[i - 1].time;
    nb.next_rot = k[i].orientation;
    nb.next_fov = 2.0f * fov - k[i - 1].yfov.value_or(0.0f);
  }
  return nb;
}

// d(position)/d(time) at key i. The centripetal Catmull-Rom derivative with respect to its own
// knot parameter (knot spacing sqrt(distance)) is scaled by the knots' rate over time at the key,
// so every segment uses the same tangent at a shared key: C1 in time.
glm::vec3 position_tangent(const CameraPath& path, std::size_t i) {
  const Neighbours nb = neighbours(path, i);
  const glm::vec3 p1 = path.keys[i].position;
  const float d01 = std::sqrt(glm::length(p1 - nb.prev_pos));
  const float d12 = std::sqrt(glm::length(nb.next_pos - p1));
  if (d01 < 1e-6f || d12 < 1e-6f) return glm::vec3(0.0f);  // a pause: stop at the key
  const glm::vec3 dk = (p1 - nb.prev_pos) / d01 - (nb.next_pos - nb.prev_pos) / (d01 + d12) +
                       (nb.next_pos - p1) / d12;
  return dk * ((d01 + d12) / (nb.next_time - nb.prev_time));
}

float fov_tangent(const CameraPath& path, std::size_t i) {
  const Neighbours nb = neighbours(path, i);
  return (nb.next_fov - nb.prev_fov) / (nb.next_time - nb.prev_time);
}

// The squad control quaternion at key i, from its neighbours on the same hemisphere.
glm::quat squad_control(const CameraPath& path, std::size_t i) {
  const Neighbours nb = neighbours(path, i);
  const glm::quat q = path.keys[i].orientation;
  glm::quat prev = glm::dot(q, nb.prev_rot) < 0.0f ? -nb.prev_rot : nb.prev_rot;
  glm::quat next = glm::dot(q, nb.next_rot) < 0.0f ? -nb.next_rot : nb.next_rot;
  return glm::intermediate(prev, q, next);
}

glm::vec3 hermite(const glm::vec3& p0, const glm::vec3& m0, const glm::vec3& p1,
                  const glm::vec3& m1, float h, float s) {
  const float s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * h * m0 + (-2 * s3 + 3 * s2) * p1 +
         (s3 - s2) * h * m1;
}

}  // namespace

std::string CameraPath::problem() const {
  if (keys.size() < 2)
    return fmt::format("path '{}' has {} keyframe(s); a path needs at least 2", name, keys.size());
  const bool has_fov = keys.front().yfov.has_value();
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const PathKey& k = keys[i];
    if (i > 0 && !(k.time > keys[i - 1].time))
      return fmt::format("path '{}': keyframe {} time {} is not after the previous ({})", name, i,
                         k.time, keys[i - 1].time);
    if (k.yfov.has_value() != has_fov)
      return fmt::format("path '{}': keyframe {} {} a fov; give every keyframe a fov or none", name,
                         i, k.yfov ? "has" : "lacks");
    const bool finite = std::isfinite(k.time) && all_finite(k.position) &&
                        std::isfinite(k.orientation.w) && std::isfinite(k.orientation.x) &&
                        std::isfinite(k.orientation.y) && std::isfinite(k.orientation.z);
    if (!finite) return fmt::format("path '{}': keyframe {} has a non-finite value", name, i);
    if (k.yfov && !(*k.yfov > 0.0f && *k.yfov < glm::pi<float>()))
      return fmt::format("path '{}': keyframe {} fov {} rad is outside (0, pi)", name, i, *k.yfov);
  }
  return {};
}

PathPose CameraPath::evaluate(float t) const {
  LANTERN_ASSERT(problem().empty());
  const float t0 = start_time(), t1 = end_time();
  if (loop) {
    t = t0 + std::fmod(t - t0, t1 - t0);
    if (t < t0) t += t1 - t0;
  }
  t = std::clamp(t, t0, t1);
  // Segment i spans keys[i] .. keys[i+1].
  auto it = std::upper_bound(keys.begin(), keys.end(), t,
                             [](float v, const PathKey& k) { return v < k.time; });
  std::size_t i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(it - keys.begin() - 1, 0));
  i = std::min(i, keys.size() - 2);
  const PathKey& a = keys[i];
  const PathKey& b = keys[i + 1];
  const float h = b.time - a.time;
  const float s = std::clamp((t - a.time) / h, 0.0f, 1.0f);

  PathPose pose;
  pose.position = hermite(a.position, position_tangent(*this, i), b.position,
                          position_tangent(*this, i + 1), h, s);
  glm::quat qb = glm::dot(a.orientation, b.orientation) < 0.0f ? -b.orientation : b.orientation;
  glm::quat sa = squad_control(*this, i);
  glm::quat sb = squad_control(*this, i + 1);
  if (glm::dot(qb, sb) < 0.0f) sb = -sb;
  pose.orientation = glm::normalize(glm::squad(a.orientation, qb, sa, sb, s));
  if (a.yfov) {
    glm::vec3 f = hermite(glm::vec3(*a.yfov), glm::vec3(fov_tangent(*this, i)), glm::vec3(*b.yfov),
                          glm::vec3(fov_tangent(*this, i + 1)), h, s);
    pose.yfov = f.x;
  }
  return pose;
}

}  // namespace lantern
