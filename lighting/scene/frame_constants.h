// FrameConstants (shaders/shared/scene.h) for a camera: Vulkan clip conventions (y down in NDC,
// depth 0..1), so pixel (0,0) is the top-left and pixel centres sit at half-integers.
#pragma once

#include <cstdint>

#include "engine/scene/camera.h"
#include "engine/world/frame_snapshot.h"
#include "shared/scene.h"

namespace lantern::lighting {

// The scene's facts FrameConstants carries (GpuScene has them: light_count(), ...).
struct FrameCounts {
  std::uint32_t lights = 0;           // in the alias table (0: none can be sampled)
  std::uint32_t instances = 0;
  std::uint32_t emissive_triangles = 0;
  std::uint32_t previous_lights = 0;  // last frame's lights: entries of the prev -> cur remap
  float scene_radius = 1.0f;          // the world's bounding-sphere radius
  std::uint32_t volumes = 0;          // participating media (scene_volumes records)
  float triangle_light_share = 0.0f;  // the emissive triangles' share of the lights' power: how
                                      // often a light draw picks from their alias table
                                      // (shared/alias_table.h; LightTable::first_group_share)
  bool lights_keep_indices = false;   // the prev -> cur remap is the identity (not read)
};

// World -> clip for `camera` rendering a width x height image (the image's aspect ratio wins
// over camera.aspect so pixels stay square; an infinite far plane becomes a finite 1e4 * znear).
glm::mat4 camera_view_proj(const Camera& camera, std::uint32_t width, std::uint32_t height);

// Constants for a static camera (previous = current, camera-cut flag set).
gpu::FrameConstants make_frame_constants(const Camera& camera, std::uint32_t width,
                                         std::uint32_t height, std::uint32_t frame_index,
                                         std::uint32_t seed, const FrameCounts& counts);

// World -> clip for a snapshot camera rendering width x height (same conventions as above).
glm::mat4 camera_view_proj(const SnapshotCamera& camera, std::uint32_t width, std::uint32_t height);

// Constants for a frame of a running world: the snapshot's camera and previous camera, frame
// index and seed; `history_valid` false (first frame, camera cut, resize) sets counts.w = 1 and
// makes the previous camera equal the current one.
gpu::FrameConstants make_frame_constants(const FrameSnapshot& snapshot, std::uint32_t width,
                                         std::uint32_t height, std::uint32_t frame_index,
                                         std::uint32_t seed, const FrameCounts& counts,
                                         bool history_valid);

}  // namespace lantern::lighting
