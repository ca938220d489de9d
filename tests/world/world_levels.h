// Levels for the world tests: cornell_lights from content/, and a small animated JSON level
// written at run time (rotate, orbit, flicker, follow_path, a camera path) so no file is committed.
#pragma once

#include <memory>
#include <vector>

#include "engine/scene/level.h"
#include "engine/world/frame_snapshot.h"
#include "engine/world/world.h"

namespace lantern::test {

std::shared_ptr<const Level> cornell_level();
std::shared_ptr<const Level> animated_level();

// Runs `frames` steps and keeps a deep copy of every snapshot.
std::vector<FrameSnapshot> run_frames(const std::shared_ptr<const Level>& level,
                                      const WorldOptions& options, int frames);

}  // namespace lantern::test
