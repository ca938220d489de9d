// Camera -> FrameConstants (frame_constants.h).
#include "lighting/scene/frame_constants.h"

#include <algorithm>

#include "engine/world/projection.h"

namespace lantern::lighting {
namespace {

// The projection both camera kinds share: the image's aspect ratio, znear kept above 0 and a
// zfar at or before znear replaced by 10^4 znear.
glm::mat4 projection(float yfov, float znear, float zfar, std::uint32_t width,
                     std::uint32_t height) {
  const float aspect = static_cast<float>(width) / static_cast<float>(std::max(height, 1u));
  const float z_near = std::max(znear, 1e-6f);
  return vulkan_perspective(yfov, aspect, z_near, zfar > z_near ? zfar : 1e4f * z_near);
}

// The fields both overloads take from the frame's counts (w of counts: 1 after a camera cut).
void set_counts(gpu::FrameConstants& fc, const FrameCounts& counts, bool cut) {
  fc.counts = glm::uvec4(counts.lights, counts.instances, counts.emissive_triangles, cut ? 1u : 0u);
  fc.environment = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  fc.history = glm::uvec4(counts.previous_lights, counts.lights_keep_indices ? 1u : 0u, 0u, 0u);
  fc.scene = glm::vec4(counts.scene_radius, counts.triangle_light_share, 0.0f, 0.0f);
  fc.media = glm::uvec4(counts.volumes, 0u, 0u, 0u);
}

}  // namespace

glm::mat4 camera_view_proj(const Camera& camera, std::uint32_t width, std::uint32_t height) {
  return projection(camera.yfov, camera.znear, camera.zfar, width, height) * camera.view_matrix();
}

gpu::FrameConstants make_frame_constants(const Camera& camera, std::uint32_t width,
                                         std::uint32_t height, std::uint32_t frame_index,
                                         std::uint32_t seed, const FrameCounts& counts) {
  gpu::FrameConstants fc{};
  fc.view_proj = camera_view_proj(camera, width, height);
  fc.prev_view_proj = fc.view_proj;
  fc.inv_view_proj = glm::inverse(fc.view_proj);
  fc.camera_position = glm::vec4(camera.position, camera.yfov);
  fc.prev_camera_position = fc.camera_position;
  fc.frame = glm::uvec4(width, height, frame_index, seed);
  set_counts(fc, counts, true);
  return fc;
}

glm::mat4 camera_view_proj(const SnapshotCamera& camera, std::uint32_t width,
                           std::uint32_t height) {
  return projection(camera.yfov, camera.znear, camera.zfar, width, height) * camera.view;
}

gpu::FrameConstants make_frame_constants(const FrameSnapshot& snapshot, std::uint32_t width,
                                         std::uint32_t height, std::uint32_t frame_index,
                                         std::uint32_t seed, const FrameCounts& counts,
                                         bool history_valid) {
  gpu::FrameConstants fc{};
  fc.view_proj = camera_view_proj(snapshot.camera, width, height);
  fc.inv_view_proj = glm::inverse(fc.view_proj);
  fc.camera_position = glm::vec4(snapshot.camera.position, snapshot.camera.yfov);
  if (history_valid) {
    fc.prev_view_proj = camera_view_proj(snapshot.prev_camera, width, height);
    fc.prev_camera_position = glm::vec4(snapshot.prev_camera.position, snapshot.prev_camera.yfov);
  } else {
    fc.prev_view_proj = fc.view_proj;
    fc.prev_camera_position = fc.camera_position;
  }
  fc.frame = glm::uvec4(width, height, frame_index, seed);
  set_counts(fc, counts, !history_valid);
  return fc;
}

}  // namespace lantern::lighting
