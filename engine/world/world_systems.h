// The world's systems, registered on a Scheduler with their declared reads and writes:
//   Simulate:  world.rotate, world.orbit, world.follow_path (write Transform, in that order),
//              world.flicker (EmissionScale), world.camera_path (CameraComponent)
//   Transform: world.transforms (WorldMatrix + PreviousTransform of moving instances),
//              world.camera_history (CameraHistory)
//   Extract:   world.extract (builds the FrameSnapshot)
// They expect the entities and resources of instantiate() plus WorldSettings, CameraCutRequest
// and FrameSnapshotSlot resources (World creates them).
#pragma once

#include "engine/sched/scheduler.h"

namespace lantern {

void register_behaviour_systems(Scheduler& scheduler);
void register_camera_systems(Scheduler& scheduler);
void register_transform_systems(Scheduler& scheduler);
void register_extract_system(Scheduler& scheduler);

// All of the above.
inline void register_world_systems(Scheduler& scheduler) {
  register_behaviour_systems(scheduler);
  register_camera_systems(scheduler);
  register_transform_systems(scheduler);
  register_extract_system(scheduler);
}

}  // namespace lantern
