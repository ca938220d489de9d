// Procedural level generators, run at load time from a level's "generators" block: parameters
// in, content appended to the level; deterministic given the seed.
#pragma once

namespace lantern {

class JsonObject;
class JsonLevelReader;

// Dispatches on params["type"] and reads the generator's parameters (unknown ones are errors).
void run_generator(JsonObject& params, JsonLevelReader& reader);

}  // namespace lantern
