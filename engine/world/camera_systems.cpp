// Camera systems: the path follower (Simulate) and the current/previous latch (Transform).
#include <fmt/format.h>

#include "engine/core/error.h"
#include "engine/world/components.h"
#include "engine/world/world_systems.h"

namespace lantern {

void register_camera_systems(Scheduler& scheduler) {
  // Poses the camera at path.evaluate(time) when a path is active; a static camera is untouched.
  scheduler.add("world.camera_path", Phase::Simulate)
      .reads<ActiveCameraPath, LevelResource>()
      .writes<CameraComponent>()
      .run([](Registry& r, const FrameTime& time) {
        const std::string& name = r.ctx().get<ActiveCameraPath>().name;
        if (name.empty()) return;
        const CameraPath* path = r.ctx().get<LevelResource>()->find_path(name);
        if (path == nullptr)
          throw RuntimeError(fmt::format("world.camera_path: no camera path named '{}'", name));
        const PathPose pose = path->evaluate(static_cast<float>(time.time));
        r.view<CameraComponent>().each([&](CameraComponent& c) {
          c.camera.position = pose.position;
          c.camera.orientation = pose.orientation;
          if (pose.yfov) c.camera.yfov = *pose.yfov;
        });
      });

  // previous ← last frame's current, current ← this frame's camera; on frame 0 both are current.
  scheduler.add("world.camera_history", Phase::Transform)
      .reads<CameraComponent>()
      .writes<CameraHistory>()
      .run([](Registry& r, const FrameTime& time) {
        r.view<const CameraComponent, CameraHistory>().each(
            [&](const CameraComponent& c, CameraHistory& h) {
              h.previous = time.frame_index == 0 ? c.camera : h.current;
              h.current = c.camera;
            });
      });
}

}  // namespace lantern
