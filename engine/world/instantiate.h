// Turns a plain-data Level into ECS entities (components.h): one entity per instance, per light,
// per volume and one for the camera, with their behaviours. The Level itself becomes the LevelResource.
#pragma once

#include <memory>

#include "engine/ecs/registry.h"
#include "engine/scene/level.h"

namespace lantern {

struct WorldEntities {
  Entity camera;
  std::size_t instances = 0;
  std::size_t lights = 0;
  std::size_t volumes = 0;
};

// Creates the entities and the LevelResource and ActiveCameraPath (the level's default path)
// resources. A follow_path behaviour or camera path naming an unknown path is an InputError.
// Call outside the scheduler (it creates entities).
WorldEntities instantiate(Registry& registry, std::shared_ptr<const Level> level);

}  // namespace lantern
