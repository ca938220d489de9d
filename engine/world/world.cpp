// World: instantiation, system registration and the frame loop (see world.h).
#include "engine/world/world.h"

#include <fmt/format.h>

#include <string>

#include "engine/core/error.h"
#include "engine/world/components.h"
#include "engine/world/world_systems.h"

namespace lantern {
namespace {

unsigned checked_threads(unsigned threads) {
  if (threads == 0) throw InputError("world: threads must be at least 1, got 0");
  return threads;
}

}  // namespace

World::World(std::shared_ptr<const Level> level, const WorldOptions& options)
    : level_(std::move(level)),
      scheduler_(checked_threads(options.threads)),
      clock_(options.fixed_dt) {
  if (!level_) throw RuntimeError("world: null level");
  if (!(options.aspect > 0.0f))
    throw InputError(fmt::format("world: aspect must be positive, got {}", options.aspect));
  entities_ = instantiate(registry_, level_);
  registry_.ctx().emplace<WorldSettings>(WorldSettings{options.seed, options.aspect});
  registry_.ctx().emplace<CameraCutRequest>();
  registry_.ctx().emplace<FrameSnapshotSlot>();
  register_world_systems(scheduler_);
}

const FrameSnapshot& World::step() {
  scheduler_.run(registry_, clock_.tick());
  return *registry_.ctx().get<FrameSnapshotSlot>().latest;
}

std::shared_ptr<const FrameSnapshot> World::latest() const {
  return registry_.ctx().get<FrameSnapshotSlot>().latest;
}

void World::request_camera_cut() {
  registry_.ctx().get<CameraCutRequest>().pending = true;
}

void World::set_camera_path(std::string_view name) {
  if (!name.empty() && level_->find_path(name) == nullptr) {
    throw InputError(fmt::format("{}: no camera path named '{}'", level_->source.string(), name));
  }
  registry_.ctx().get<ActiveCameraPath>().name = std::string(name);
}

}  // namespace lantern
