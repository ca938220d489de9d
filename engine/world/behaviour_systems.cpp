// Simulate-phase behaviour systems: rotate, orbit, follow_path move Transforms; flicker scales
// emission. Each evaluates its behaviour at the frame's absolute time (behaviour_eval.h).
#include "engine/world/behaviour_eval.h"
#include "engine/world/components.h"
#include "engine/world/world_systems.h"

namespace lantern {

void register_behaviour_systems(Scheduler& scheduler) {
  scheduler.add("world.rotate", Phase::Simulate)
      .reads<RotateComponent>()
      .writes<Transform>()
      .run([](Registry& r, const FrameTime& time) {
        r.view<const RotateComponent, Transform>().each(
            [&](const RotateComponent& rot, Transform& pose) {
              pose.rotation = rotate_at(rot.params, rot.base_rotation, time.time);
            });
      });

  scheduler.add("world.orbit", Phase::Simulate)
      .reads<OrbitComponent>()
      .writes<Transform>()
      .run([](Registry& r, const FrameTime& time) {
        r.view<const OrbitComponent, Transform>().each(
            [&](const OrbitComponent& orbit, Transform& pose) {
              pose.translation = orbit_at(orbit.params, time.time);
            });
      });

  scheduler.add("world.follow_path", Phase::Simulate)
      .reads<FollowPathComponent, LevelResource>()
      .writes<Transform>()
      .run([](Registry& r, const FrameTime& time) {
        const Level& level = *r.ctx().get<LevelResource>();
        r.view<const FollowPathComponent, Transform>().each(
            [&](const FollowPathComponent& follow, Transform& pose) {
              const CameraPath& path = level.paths[follow.path];
              const PathPose p = path.evaluate(follow_path_time(follow.params, path, time.time));
              pose.translation = p.position;
              pose.rotation = p.orientation;
            });
      });

  scheduler.add("world.flicker", Phase::Simulate)
      .reads<FlickerComponent, StableId, WorldSettings>()
      .writes<EmissionScale>()
      .run([](Registry& r, const FrameTime& time) {
        const std::uint64_t seed = r.ctx().get<WorldSettings>().seed;
        r.view<const FlickerComponent, const StableId, EmissionScale>().each(
            [&](const FlickerComponent& flicker, const StableId& id, EmissionScale& scale) {
              scale.value = flicker_at(flicker.params, seed, id, time.time);
            });
      });
}

}  // namespace lantern
