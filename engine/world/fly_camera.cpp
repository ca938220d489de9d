// world.fly_camera (see fly_camera.h).
#include "engine/world/fly_camera.h"

#include <algorithm>
#include <cmath>

#include "engine/world/components.h"
#include "engine/world/world.h"

namespace lantern {
namespace {

constexpr float kMaxPitch = 1.5533f;  // 89 degrees

}  // namespace

glm::vec2 yaw_pitch_of(const glm::quat& orientation) {
  const glm::vec3 f = glm::normalize(orientation * glm::vec3(0.0f, 0.0f, -1.0f));
  const float yaw = std::atan2(-f.x, -f.z);
  const float pitch = std::asin(std::clamp(f.y, -1.0f, 1.0f));
  return {yaw, std::clamp(pitch, -kMaxPitch, kMaxPitch)};
}

glm::quat orientation_of(float yaw, float pitch) {
  return glm::normalize(glm::angleAxis(yaw, glm::vec3(0.0f, 1.0f, 0.0f)) *
                        glm::angleAxis(pitch, glm::vec3(1.0f, 0.0f, 0.0f)));
}

void enable_fly_camera(World& world) {
  world.registry().ctx().emplace<FlyCamera>();
  // Moves the camera by this frame's input while manual control is on. Runs after
  // world.camera_path (declared later, same component), which is idle then (no active path).
  world.scheduler()
      .add("world.fly_camera", Phase::Simulate)
      .reads<ActiveCameraPath>()
      .writes<FlyCamera, CameraComponent>()
      .run([](Registry& r, const FrameTime& time) {
        FlyCamera& fly = r.ctx().get<FlyCamera>();
        if (!fly.active) return;
        const FlyCameraInput& in = fly.input;
        fly.yaw = std::remainder(fly.yaw + in.yaw, 2.0f * glm::pi<float>());
        fly.pitch = std::clamp(fly.pitch + in.pitch, -kMaxPitch, kMaxPitch);
        const glm::quat orientation = orientation_of(fly.yaw, fly.pitch);
        const float dt = in.dt > 0.0f ? in.dt : static_cast<float>(time.dt);
        const glm::vec3 right = orientation * glm::vec3(1.0f, 0.0f, 0.0f);
        const glm::vec3 forward = orientation * glm::vec3(0.0f, 0.0f, -1.0f);
        const glm::vec3 move = glm::clamp(in.move, glm::vec3(-1.0f), glm::vec3(1.0f));
        const glm::vec3 step =
            (right * move.x + glm::vec3(0.0f, 1.0f, 0.0f) * move.y + forward * move.z) *
            (fly.speed * std::max(in.boost, 0.0f) * dt);
        r.view<CameraComponent>().each([&](CameraComponent& c) {
          c.camera.position += step;
          c.camera.orientation = orientation;
        });
      });
}

FlyCamera& fly_camera(World& world) {
  return world.registry().ctx().get<FlyCamera>();
}

void take_manual_control(World& world) {
  FlyCamera& fly = fly_camera(world);
  if (fly.active) return;
  Registry& r = world.registry();
  r.view<const CameraComponent>().each([&](const CameraComponent& c) {
    const glm::vec2 yp = yaw_pitch_of(c.camera.orientation);
    fly.yaw = yp.x;
    fly.pitch = yp.y;
  });
  fly.active = true;
  world.set_camera_path("");
}

void resume_camera_path(World& world) {
  FlyCamera& fly = fly_camera(world);
  fly.active = false;
  fly.input = {};
  world.set_camera_path(world.level().camera_path);
  if (!world.level().camera_path.empty()) world.request_camera_cut();
}

}  // namespace lantern
