// Procedural level generators, run at load time from a level's "generators" block: parameters
// in, content appended to the level; deterministic given the seed.
#pragma once

#include <string>

namespace lantern {

struct Level;
class JsonObject;
class JsonLevelReader;

// Dispatches on params["type"] and reads the generator's parameters (unknown ones are errors).
void run_generator(JsonObject& params, JsonLevelReader& reader);

// After a generator added its camera path `path_name`: the level's camera follows it unless the
// level chose another path, and a level without a camera of its own starts at the path's first
// pose (60 degree vertical field of view).
void use_generated_camera_path(Level& level, const std::string& path_name);

}  // namespace lantern
