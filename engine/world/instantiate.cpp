// Level → entities (see instantiate.h).
#include "engine/world/instantiate.h"

#include <fmt/format.h>

#include <string>
#include <type_traits>
#include <variant>

#include "engine/core/error.h"
#include "engine/world/components.h"

namespace lantern {
namespace {

std::uint32_t path_index(const Level& level, const std::string& name, const std::string& owner) {
  for (std::size_t i = 0; i < level.paths.size(); ++i)
    if (level.paths[i].name == name) return static_cast<std::uint32_t>(i);
  throw InputError(fmt::format("{}: {} follows path '{}', which the level does not define",
                               level.source.string(), owner, name));
}

// Adds the behaviour's component; returns true when it moves the entity (changes its Transform).
bool add_behaviour(Registry& registry, Entity e, const Level& level, const Behaviour& behaviour,
                   const Transform& pose, const std::string& owner) {
  return std::visit(
      [&](const auto& b) {
        using B = std::decay_t<decltype(b)>;
        if constexpr (std::is_same_v<B, RotateBehaviour>) {
          registry.emplace<RotateComponent>(e, RotateComponent{b, pose.rotation});
          return true;
        } else if constexpr (std::is_same_v<B, OrbitBehaviour>) {
          registry.emplace<OrbitComponent>(e, OrbitComponent{b});
          return true;
        } else if constexpr (std::is_same_v<B, FlickerBehaviour>) {
          registry.emplace<FlickerComponent>(e, FlickerComponent{b});
          return false;
        } else {
          static_assert(std::is_same_v<B, FollowPathBehaviour>);
          registry.emplace<FollowPathComponent>(
              e, FollowPathComponent{b, path_index(level, b.path, owner)});
          return true;
        }
      },
      behaviour);
}

}  // namespace

WorldEntities instantiate(Registry& registry, std::shared_ptr<const Level> level_ptr) {
  if (!level_ptr) throw RuntimeError("instantiate: null level");
  const Level& level = *level_ptr;
  WorldEntities out;

  for (std::size_t i = 0; i < level.instances.size(); ++i) {
    const Instance& inst = level.instances[i];
    const Entity e = registry.create();
    const auto id = static_cast<std::uint32_t>(i);
    registry.emplace<StableId>(e, StableId{EntityKind::Instance, id});
    registry.emplace<Transform>(e, inst.transform);
    registry.emplace<WorldMatrix>(e, WorldMatrix{inst.world});
    registry.emplace<PreviousTransform>(e, PreviousTransform{inst.world});
    registry.emplace<MeshRef>(e, MeshRef{inst.mesh});
    registry.emplace<MaterialRef>(e, MaterialRef{inst.material});
    registry.emplace<EmissionScale>(e);
    if (inst.behaviour) {
      const std::string owner = fmt::format("instance {} '{}'", i, inst.name);
      if (add_behaviour(registry, e, level, *inst.behaviour, inst.transform, owner)) {
        registry.emplace<DynamicTransform>(e);
      }
    }
  }
  out.instances = level.instances.size();

  for (std::size_t i = 0; i < level.lights.size(); ++i) {
    const Light& light = level.lights[i];
    const Entity e = registry.create();
    const Transform pose{light.position, light.rotation, glm::vec3(1.0f)};
    registry.emplace<StableId>(e, StableId{EntityKind::Light, static_cast<std::uint32_t>(i)});
    registry.emplace<Transform>(e, pose);
    registry.emplace<LightComponent>(e, LightComponent{static_cast<std::uint32_t>(i)});
    registry.emplace<EmissionScale>(e);
    if (light.behaviour) {
      add_behaviour(registry, e, level, *light.behaviour, pose,
                    fmt::format("light {} '{}'", i, light.name));
    }
  }
  out.lights = level.lights.size();

  for (std::size_t i = 0; i < level.volumes.size(); ++i) {
    const Volume& volume = level.volumes[i];
    const Entity e = registry.create();
    const auto id = static_cast<std::uint32_t>(i);
    const glm::mat4 placement = volume.transform.matrix();
    registry.emplace<StableId>(e, StableId{EntityKind::Volume, id});
    registry.emplace<Transform>(e, volume.transform);
    registry.emplace<WorldMatrix>(e, WorldMatrix{placement});
    registry.emplace<PreviousTransform>(e, PreviousTransform{placement});
    registry.emplace<VolumeComponent>(e, VolumeComponent{id});
    if (volume.behaviour &&
        add_behaviour(registry, e, level, *volume.behaviour, volume.transform,
                      fmt::format("volume {} '{}'", i, volume.name)))
      registry.emplace<DynamicTransform>(e);
  }
  out.volumes = level.volumes.size();

  out.camera = registry.create();
  registry.emplace<CameraComponent>(out.camera, CameraComponent{level.camera});
  registry.emplace<CameraHistory>(out.camera, CameraHistory{level.camera, level.camera});

  if (!level.camera_path.empty() && level.find_path(level.camera_path) == nullptr) {
    throw InputError(
        fmt::format("{}: the camera follows path '{}', which the level does not define",
                    level.source.string(), level.camera_path));
  }
  registry.ctx().emplace<ActiveCameraPath>(ActiveCameraPath{level.camera_path});
  registry.ctx().emplace<LevelResource>(std::move(level_ptr));
  return out;
}

}  // namespace lantern
