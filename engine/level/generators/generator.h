// Procedural level generators, run at load time from a level's "generators" block: parameters
// in, content appended to the level; deterministic given the seed.
#pragma once

#include <functional>
#include <glm/vec3.hpp>
#include <string>

#include "engine/scene/material.h"

namespace lantern {

struct Level;
class JsonObject;
class JsonLevelReader;

// Dispatches on params["type"] and reads the generator's parameters (unknown ones are errors).
void run_generator(JsonObject& params, JsonLevelReader& reader);

// A generated surface: a dielectric (metallic 0; glTF's default of 1 would make it a metal) of
// base colour `color` and perceptual `roughness`.
Material generated_surface(const std::string& name, glm::vec3 color, float roughness);

// A generated emitter: `color` x `radiance` (emissive factor and strength) over a dark rough
// generated surface.
Material generated_emitter(const std::string& name, glm::vec3 color, float radiance);

// After a generator added its camera path `path_name`: the level's camera follows it unless the
// level chose another path, and a level without a camera of its own starts at the path's first
// pose (60 degree vertical field of view).
void use_generated_camera_path(Level& level, const std::string& path_name);

// Where a generated camera loop is at step i of `steps`: the eye and the point it looks at.
struct LoopPose {
  glm::vec3 eye;
  glm::vec3 target;
};

// Adds the looping camera path `path_name` (unless the level already has one of that name):
// steps + 1 keys evenly spaced over `duration` seconds at pose(0) .. pose(steps), the last key
// turned as the first so the loop closes; then use_generated_camera_path.
void add_generated_camera_loop(Level& level, const std::string& path_name, float duration,
                               int steps, const std::function<LoopPose(int)>& pose);

}  // namespace lantern
