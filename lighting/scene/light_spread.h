// How much the light reaching a level's surfaces depends on where they are, beyond what drawing
// lights in proportion to their power accounts for: the level's light spread. At a surface point
// x, a light drawn by power (pdf p) gives the one-sample estimate w = c(x, y) / p(y) of the
// unshadowed light there (c: light_eval's contribution on a white Lambertian surface, either
// side); its relative variance E[w^2] / E[w]^2 - 1 says how many power-drawn candidates it takes
// to find the lights that matter at x. Small where every light reaches every surface alike
// (panels over a floor, however finely subdivided), large where each light lights only its
// surroundings (lanterns beside stalls among many others). ReSTIR's light presampling tiles and
// local light lists are for the second kind (RestirIntegrator): the spread lets a level of the
// first kind skip them. No Vulkan here.
#pragma once

#include <cstdint>

namespace lantern::lighting {

struct SceneData;

struct LightSpread {
  // The relative variance above at surface points spread over the level's non-emitting surfaces
  // by area, averaged over the points any light reaches; 0 without lights or surfaces.
  float spread = 0.0f;
  std::uint32_t points = 0;  // surface points that some light reaches (of those tried)
};

// Estimated with `points` surface points and `draws` power draws at each (deterministic for a
// seed). Points on emitting triangles are not tried unless every triangle emits.
LightSpread measure_light_spread(const SceneData& scene, std::uint32_t points = 256,
                                 std::uint32_t draws = 256, std::uint32_t seed = 1);

}  // namespace lantern::lighting
