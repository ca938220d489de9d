// Extract phase: copies the world into an immutable FrameSnapshot (frame_snapshot.h). The system
// only reads the world; it writes the snapshot slot and consumes a pending camera-cut request.
#include <algorithm>
#include <memory>

#include "engine/world/components.h"
#include "engine/world/frame_snapshot.h"
#include "engine/world/projection.h"
#include "engine/world/world_systems.h"

namespace lantern {
namespace {

SnapshotCamera snapshot_camera(const Camera& c, float default_aspect) {
  SnapshotCamera s;
  s.position = c.position;
  s.orientation = c.orientation;
  s.yfov = c.yfov;
  s.aspect = c.aspect > 0.0f ? c.aspect : default_aspect;
  s.znear = c.znear;
  s.zfar = c.zfar;
  s.view = c.view_matrix();
  s.projection = vulkan_perspective(s.yfov, s.aspect, s.znear, s.zfar);
  return s;
}

// Reuses last frame's snapshot storage when nobody else holds it any more.
std::shared_ptr<FrameSnapshot> writable_snapshot(FrameSnapshotSlot& slot) {
  if (slot.latest && slot.latest.use_count() == 1) {
    auto reused = std::const_pointer_cast<FrameSnapshot>(std::move(slot.latest));
    reused->instances.clear();
    reused->lights.clear();
    reused->volumes.clear();
    return reused;
  }
  return std::make_shared<FrameSnapshot>();
}

}  // namespace

void register_extract_system(Scheduler& scheduler) {
  scheduler.add("world.extract", Phase::Extract)
      .reads<StableId, WorldMatrix, PreviousTransform, MeshRef, MaterialRef, EmissionScale,
             LightComponent, VolumeComponent, Transform, CameraHistory, LevelResource,
             WorldSettings>()
      .writes<FrameSnapshotSlot, CameraCutRequest>()
      .run([](Registry& r, const FrameTime& time) {
        const WorldSettings& settings = r.ctx().get<WorldSettings>();
        const std::shared_ptr<const Level>& level = r.ctx().get<LevelResource>();
        FrameSnapshotSlot& slot = r.ctx().get<FrameSnapshotSlot>();
        CameraCutRequest& cut = r.ctx().get<CameraCutRequest>();
        std::shared_ptr<FrameSnapshot> snap = writable_snapshot(slot);

        snap->frame_index = time.frame_index;
        snap->time = time.time;
        snap->dt = time.dt;
        snap->seed = settings.seed;
        snap->camera_cut = time.frame_index == 0 || cut.pending;
        cut.pending = false;
        snap->level = level;

        r.view<const CameraHistory>().each([&](const CameraHistory& h) {
          snap->camera = snapshot_camera(h.current, settings.aspect);
          snap->prev_camera = snapshot_camera(h.previous, settings.aspect);
        });

        r.view<const StableId, const WorldMatrix, const PreviousTransform, const MeshRef,
               const MaterialRef, const EmissionScale>()
            .each([&](const StableId& id, const WorldMatrix& world, const PreviousTransform& prev,
                      const MeshRef& mesh, const MaterialRef& material,
                      const EmissionScale& scale) {
              snap->instances.push_back(SnapshotInstance{world.object_to_world,
                                                         prev.object_to_world, id.value, mesh.index,
                                                         material.index, scale.value});
            });
        std::sort(snap->instances.begin(), snap->instances.end(),
                  [](const SnapshotInstance& a, const SnapshotInstance& b) {
                    return a.stable_id < b.stable_id;
                  });

        r.view<const StableId, const LightComponent, const Transform, const EmissionScale>().each(
            [&](const StableId& id, const LightComponent& lc, const Transform& pose,
                const EmissionScale& scale) {
              const Light& light = level->lights[lc.index];
              SnapshotLight s;
              s.position = pose.translation;
              s.stable_id = id.value;
              s.direction = glm::normalize(pose.rotation * glm::vec3(0.0f, 0.0f, -1.0f));
              s.intensity = light.intensity * scale.value;
              s.color = light.color;
              s.type = static_cast<std::uint32_t>(light.type);
              s.range = light.range;
              s.inner_cone = light.inner_cone;
              s.outer_cone = light.outer_cone;
              snap->lights.push_back(s);
            });
        std::sort(snap->lights.begin(), snap->lights.end(),
                  [](const SnapshotLight& a, const SnapshotLight& b) {
                    return a.stable_id < b.stable_id;
                  });

        r.view<const StableId, const VolumeComponent, const WorldMatrix,
               const PreviousTransform>()
            .each([&](const StableId& id, const VolumeComponent&, const WorldMatrix& world,
                      const PreviousTransform& prev) {
              SnapshotVolume s;
              s.object_to_world = world.object_to_world;
              s.prev_object_to_world = prev.object_to_world;
              s.stable_id = id.value;
              snap->volumes.push_back(s);
            });
        std::sort(snap->volumes.begin(), snap->volumes.end(),
                  [](const SnapshotVolume& a, const SnapshotVolume& b) {
                    return a.stable_id < b.stable_id;
                  });

        slot.latest = std::move(snap);
      });
}

}  // namespace lantern
