// Transform phase: moving instances latch last frame's world matrix, then compose the new one
// from their Transform. Static instances keep the Level's matrix (and previous == current).
#include "engine/world/components.h"
#include "engine/world/world_systems.h"

namespace lantern {

void register_transform_systems(Scheduler& scheduler) {
  scheduler.add("world.transforms", Phase::Transform)
      .reads<Transform, DynamicTransform>()
      .writes<WorldMatrix, PreviousTransform>()
      .run([](Registry& r, const FrameTime& time) {
        r.view<const Transform, const DynamicTransform, WorldMatrix, PreviousTransform>().each(
            [&](const Transform& pose, const DynamicTransform&, WorldMatrix& world,
                PreviousTransform& prev) {
              const glm::mat4 m = pose.matrix();
              prev.object_to_world = time.frame_index == 0 ? m : world.object_to_world;
              world.object_to_world = m;
            });
      });
}

}  // namespace lantern
