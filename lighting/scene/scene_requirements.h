// What the lighting module builds for a level, and why (`lantern info`): the light-sampling
// structure sized by the emitters present, environment sampling only with an environment map,
// the visibility structure, the geometry buffers and the per-frame images at a render size, each
// with its memory. Computed on the CPU from the same SceneData/EnvironmentDistribution the
// renderer uploads, so the figures are the real buffer sizes (one zeroed element stands in for
// an empty array, as on the device).
#pragma once

#include <cstdint>

#include "engine/scene/level.h"
#include "engine/scene/level_summary.h"
#include "lighting/gbuffer/gbuffer_method.h"
#include "lighting/visibility/visibility_backend.h"

namespace lantern::lighting {

// Adds the sections "light_sampling", "environment", "visibility", "geometry", "textures",
// "volumes" (volume_requirements.h), "per_frame" and "shader_variants" to summary.enabled;
// `visibility` is the backend chosen for the device (named with its reason; ray query adds its
// BLAS/TLAS estimate), `gbuffer` the --set gbuffer= method (Auto: what the frame would pick).
// Throws InputError on bad level data.
void describe_requirements(const Level& level, std::uint32_t width, std::uint32_t height,
                           LevelSummary& summary, const VisibilityChoice& visibility = {},
                           GBufferMethod gbuffer = GBufferMethod::Auto);

}  // namespace lantern::lighting
