// Flashlight, light groups and spawned lights (play_lights.h).
#include "apps/lantern/play/play_lights.h"

#include <algorithm>
#include <cmath>

#include "engine/world/components.h"
#include "engine/world/world.h"
#include "lighting/scene/gpu_scene.h"

namespace lantern::app {
namespace {

// Marks a light that follows the camera; offset in the camera's frame (metres).
struct AttachToCamera {
  glm::vec3 offset{0.0f};
};

// Saved while the emissive surfaces are switched off.
struct SavedEmission {
  float scale = 1.0f;
  std::optional<FlickerComponent> flicker;
};

}  // namespace

float level_radius(const Level& level) {
  Aabb box;
  for (const Instance& inst : level.instances) {
    box.grow(level.meshes.at(inst.mesh).bounds.transformed(inst.world));
  }
  const float r = box.empty() ? 1.0f : 0.5f * glm::length(box.extent());
  return std::isfinite(r) ? std::max(r, 0.1f) : 1.0f;
}

PlayLightSlots add_play_lights(Level& level, float exposure) {
  const float r = level_radius(level);
  // Mid grey at distance d from a point light of intensity I on a diffuse surface of albedo ~0.5:
  // L = 0.5/pi * I/d^2 = 0.18/exposure  ->  I = 1.1 d^2 / exposure.
  const float e = exposure > 0.0f && std::isfinite(exposure) ? exposure : 1.0f;
  const float spawn_d = 0.15f * r;
  const float flash_d = 0.3f * r;
  PlayLightSlots slots;
  slots.level_lights = static_cast<std::uint32_t>(level.lights.size());
  Light flash;
  flash.name = "play.flashlight";
  flash.type = LightType::Spot;
  flash.color = glm::vec3(1.0f, 0.95f, 0.85f);
  flash.intensity = 4.0f * 1.1f * flash_d * flash_d / e;
  flash.inner_cone = 0.25f;
  flash.outer_cone = 0.45f;
  slots.flashlight = static_cast<std::uint32_t>(level.lights.size());
  level.lights.push_back(flash);
  slots.first_spawn = static_cast<std::uint32_t>(level.lights.size());
  for (std::uint32_t i = 0; i < kSpawnSlots; ++i) {
    Light spawn;
    spawn.name = "play.spawn." + std::to_string(i);
    spawn.type = LightType::Point;
    // A few hues so several spawned lights can be told apart.
    const float h = static_cast<float>(i) / static_cast<float>(kSpawnSlots);
    spawn.color =
        glm::clamp(
            glm::abs(glm::fract(glm::vec3(h) + glm::vec3(1.0f, 2.0f / 3.0f, 1.0f / 3.0f)) * 6.0f -
                     3.0f) -
                1.0f,
            0.0f, 1.0f) *
            0.6f +
        0.4f;
    spawn.intensity = 1.1f * spawn_d * spawn_d / e;
    level.lights.push_back(spawn);
  }
  return slots;
}

PlayLights::PlayLights(World& world, const PlayLightSlots& slots)
    : world_(world), slots_(slots), spawn_(kSpawnSlots) {
  Registry& r = world_.registry();
  std::vector<Entity> remove;
  r.view<const StableId, const LightComponent>().each(
      [&](Entity e, const StableId&, const LightComponent& lc) {
        if (lc.index >= slots_.level_lights) remove.push_back(e);
      });
  for (Entity e : remove) r.destroy(e);

  world_.scheduler()
      .add("play.attach_to_camera", Phase::Simulate)
      .reads<CameraComponent, AttachToCamera>()
      .writes<Transform>()
      .run([](Registry& reg, const FrameTime&) {
        Camera camera;
        reg.view<const CameraComponent>().each(
            [&](const CameraComponent& c) { camera = c.camera; });
        reg.view<const AttachToCamera, Transform>().each(
            [&](const AttachToCamera& a, Transform& t) {
              t.translation = camera.position + camera.orientation * a.offset;
              t.rotation = camera.orientation;
            });
      });
}

Entity PlayLights::add_light_entity(std::uint32_t index) {
  Registry& r = world_.registry();
  const Light& light = world_.level().lights.at(index);
  const Entity e = r.create();
  r.emplace<StableId>(e, StableId{EntityKind::Light, index});
  r.emplace<Transform>(e, Transform{light.position, light.rotation, glm::vec3(1.0f)});
  r.emplace<LightComponent>(e, LightComponent{index});
  r.emplace<EmissionScale>(e);
  return e;
}

void PlayLights::toggle_flashlight() {
  Registry& r = world_.registry();
  if (flashlight_) {
    r.destroy(*flashlight_);
    flashlight_.reset();
    return;
  }
  const Entity e = add_light_entity(slots_.flashlight);
  // Slightly right of and below the eye, like a torch held in the hand.
  const float r_level = level_radius(world_.level());
  r.emplace<AttachToCamera>(e, AttachToCamera{glm::vec3(0.02f, -0.02f, 0.0f) * r_level});
  flashlight_ = e;
}

void PlayLights::toggle_level_lights() {
  Registry& r = world_.registry();
  level_lights_on_ = !level_lights_on_;
  if (!level_lights_on_) {
    std::vector<Entity> remove;
    r.view<const LightComponent>().each([&](Entity e, const LightComponent& lc) {
      if (lc.index < slots_.level_lights) remove.push_back(e);
    });
    for (Entity e : remove) r.destroy(e);
    return;
  }
  // Back with their behaviours (orbits, flicker) as the level defines them.
  for (std::uint32_t i = 0; i < slots_.level_lights; ++i) {
    const Entity e = add_light_entity(i);
    const Light& light = world_.level().lights[i];
    if (!light.behaviour) continue;
    std::visit(
        [&](const auto& b) {
          using B = std::decay_t<decltype(b)>;
          if constexpr (std::is_same_v<B, RotateBehaviour>) {
            r.emplace<RotateComponent>(e, RotateComponent{b, light.rotation});
          } else if constexpr (std::is_same_v<B, OrbitBehaviour>) {
            r.emplace<OrbitComponent>(e, OrbitComponent{b});
          } else if constexpr (std::is_same_v<B, FlickerBehaviour>) {
            r.emplace<FlickerComponent>(e, FlickerComponent{b});
          } else {
            const Level& level = world_.level();
            for (std::size_t p = 0; p < level.paths.size(); ++p)
              if (level.paths[p].name == b.path)
                r.emplace<FollowPathComponent>(
                    e, FollowPathComponent{b, static_cast<std::uint32_t>(p)});
          }
        },
        *light.behaviour);
  }
}

void PlayLights::toggle_emissive_surfaces() {
  Registry& r = world_.registry();
  const Level& level = world_.level();
  emissive_on_ = !emissive_on_;
  std::vector<Entity> entities;
  r.view<const StableId, const MaterialRef, EmissionScale>().each(
      [&](Entity e, const StableId&, const MaterialRef& m, EmissionScale&) {
        if (level.materials.at(m.index).emissive()) entities.push_back(e);
      });
  for (Entity e : entities) {
    if (!emissive_on_) {
      SavedEmission saved{r.get<EmissionScale>(e).value, std::nullopt};
      if (const FlickerComponent* f = r.try_get<FlickerComponent>(e)) {
        saved.flicker = *f;
        r.remove<FlickerComponent>(e);
      }
      r.get<EmissionScale>(e).value = 0.0f;
      if (r.has<SavedEmission>(e)) r.remove<SavedEmission>(e);
      r.emplace<SavedEmission>(e, saved);
    } else if (const SavedEmission* saved = r.try_get<SavedEmission>(e)) {
      r.get<EmissionScale>(e).value = saved->scale;
      if (saved->flicker) r.emplace<FlickerComponent>(e, *saved->flicker);
      r.remove<SavedEmission>(e);
    }
  }
}

bool PlayLights::spawn_light(const lighting::GpuScene& scene) {
  Camera camera;
  world_.registry().view<const CameraComponent>().each(
      [&](const CameraComponent& c) { camera = c.camera; });
  const glm::vec3 dir = glm::normalize(camera.forward());
  const float r_level = level_radius(world_.level());
  gpu::BvhRay ray;
  ray.origin = gpu::vec4(camera.position, 0.0f);
  ray.direction = gpu::vec4(dir, 4.0f * r_level + 1.0f);
  gpu::BvhHit hit{};
  if (!scene.data().bvh.trace_closest(ray, hit)) return false;
  // Back off towards the camera so the light sits in front of the surface.
  const float back = std::min(0.05f * r_level, 0.5f * hit.t);
  const glm::vec3 position = camera.position + dir * (hit.t - back);

  Registry& r = world_.registry();
  const std::uint32_t slot = next_spawn_;
  next_spawn_ = (next_spawn_ + 1) % kSpawnSlots;
  if (spawn_[slot]) {
    r.destroy(*spawn_[slot]);
  } else {
    ++spawned_count_;
  }
  const Entity e = add_light_entity(slots_.first_spawn + slot);
  r.get<Transform>(e).translation = position;
  spawn_[slot] = e;
  last_spawn_ = position;
  return true;
}

void PlayLights::clear_spawned() {
  for (auto& s : spawn_) {
    if (s) world_.registry().destroy(*s);
    s.reset();
  }
  spawned_count_ = 0;
  next_spawn_ = 0;
}

}  // namespace lantern::app
