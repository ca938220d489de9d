// A running world: a Level instantiated into an ECS registry, the world systems on a scheduler,
// and a fixed-step clock. Each step() simulates one frame and returns its immutable snapshot.
//
//   World world(std::make_shared<const Level>(load_level_argument("cornell_lights")),
//               {.threads = 2, .seed = 1, .fixed_dt = 1.0 / 60.0});
//   const FrameSnapshot& frame = world.step();
//
// Same level, seed and dt give bitwise-identical snapshots whatever the thread count.
#pragma once

#include <cstdint>
#include <memory>
#include <string_view>

#include "engine/core/clock.h"
#include "engine/ecs/registry.h"
#include "engine/sched/scheduler.h"
#include "engine/world/frame_snapshot.h"
#include "engine/world/instantiate.h"

namespace lantern {

struct WorldOptions {
  unsigned threads = 1;            // scheduler worker threads (1 = run inline)
  std::uint64_t seed = 1;          // root of the world's random numbers (flicker)
  double fixed_dt = 1.0 / 60.0;    // seconds per step
  float aspect = 640.0f / 360.0f;  // output width / height when the level's camera gives none
};

class World {
 public:
  // Throws InputError for bad options (threads 0, dt not positive) or dangling path names.
  World(std::shared_ptr<const Level> level, const WorldOptions& options);

  // Simulates one frame (Input → Simulate → Transform → Extract → Render) and returns its
  // snapshot, valid until the next step(); latest() shares ownership instead.
  const FrameSnapshot& step();
  std::shared_ptr<const FrameSnapshot> latest() const;

  // The next snapshot has camera_cut set (temporal history must be dropped).
  void request_camera_cut();
  // Makes the camera follow another path of the level ("" = stay where it is). InputError if
  // the level has no such path.
  void set_camera_path(std::string_view name);

  // For registering more systems (lighting's) and for inspection.
  Registry& registry() { return registry_; }
  Scheduler& scheduler() { return scheduler_; }
  const Level& level() const { return *level_; }
  const WorldEntities& entities() const { return entities_; }

 private:
  std::shared_ptr<const Level> level_;
  Registry registry_;
  Scheduler scheduler_;
  FixedClock clock_;
  WorldEntities entities_;
};

}  // namespace lantern
