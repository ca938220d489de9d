// The play loop. Per frame:
//   poll window events + script events -> PlayInput; shader sources polled for hot reload;
//   begin_frame (skipped while minimised); follow the render size; keys and the F1 panel; fly
//   camera input into the World; world.step(); the frame through lighting::FrameSession (the one
//   frame loop): scene.upload -> gbuffer -> integrator [-> play.accumulate while still, a
//   progressive integrator: its HDR hook] -> frame.output (filmic) [-> play.ui ->
//   play.ui_composite: its output hook] -> target.present. The session's GPU timestamps per pass
//   (read back when the frame slot comes round again) feed the panel's graphs.
#include "apps/lantern/play/play_session.h"

#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <span>
#include <string_view>
#include <utility>

#include "apps/lantern/play/play_lights.h"
#include "apps/lantern/play/play_panel.h"
#include "apps/lantern/play/play_ui.h"
#include "apps/lantern/play/shader_reload.h"
#include "engine/core/error.h"
#include "engine/core/log.h"
#include "engine/level/level_loader.h"
#include "engine/perf/statistics.h"
#include "engine/world/components.h"
#include "engine/world/fly_camera.h"
#include "engine/world/world.h"
#include "lighting/frame/frame_renderer.h"
#include "lighting/frame/frame_session.h"
#include "lighting/integrators/auto_exposure.h"
#include "lighting/integrators/offline_render.h"
#include "play/play_ui.h"
#include "runtime/core/device.h"
#include "runtime/gpu/bindings.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/graph/render_graph.h"
#include "runtime/target/window_target.h"
#include "runtime/window/presentation.h"
#include "runtime/window/window.h"

namespace lantern::app {
namespace {

namespace graph = runtime::graph;
using Clock = std::chrono::steady_clock;

constexpr graph::AccessState kAnyPriorUse{
    VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
    VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED};
constexpr float kLookRadiansPerUnit = 0.004f;
// Frames before play's frame-interval report counts (pipelines settle, dynamic resolution finds
// its size).
constexpr std::size_t kWarmUpFrames = 30;
// GPU timestamps on one frame in this many (FrameSession::set_timing_interval): the panel's
// per-pass times are samples anyway, and on lavapipe each pass's timestamp pair costs ~60 us of
// every frame it is recorded in.
constexpr std::uint32_t kPlayTimingInterval = 8;

// The renderer and everything built from one ShaderLibrary: replaced as a whole on an integrator
// switch or a shader reload (the library outlives what was built from it).
struct RenderBundle {
  const lighting::IntegratorEntry* integrator = nullptr;  // the registry row the renderer runs
  std::unique_ptr<runtime::ShaderLibrary> shaders;
  std::unique_ptr<lighting::FrameRenderer> renderer;
  std::unique_ptr<runtime::ComputePipeline> accumulate;
};

lighting::IntegratorConfig config_for(const PanelState& panel,
                                      const lighting::IntegratorConfig& base) {
  lighting::IntegratorConfig c;
  c.name = panel.integrator;
  c.preset = panel.preset;
  c.visibility = base.visibility;  // the backend stays across switches and reloads
  c.gbuffer = base.gbuffer;        // and so does the G-buffer method
  if (c.name == lighting::RestirIntegrator::kName) {
    c.settings = lighting::describe(panel.restir);
  } else if (c.name == base.name) {
    c.settings = base.settings;
    c.spp = base.spp;
  }
  return c;
}

RenderBundle build_bundle(runtime::Device& device, const ShaderReloader& reloader,
                          const std::shared_ptr<const Level>& level,
                          const lighting::IntegratorConfig& config, std::uint32_t width,
                          std::uint32_t height, std::uint32_t seed) {
  RenderBundle b;
  b.integrator = &lighting::find_integrator(config.name);
  b.shaders = reloader.make_library();
  b.renderer = std::make_unique<lighting::FrameRenderer>(
      device, *b.shaders, level, lighting::make_integrator(device, *b.shaders, config), width,
      height, seed);
  b.renderer->set_gbuffer_method(config.gbuffer);
  b.renderer->warm_up();
  b.accumulate = std::make_unique<runtime::ComputePipeline>(
      device, b.shaders->load("play/play_accumulate.comp"),
      runtime::ComputePipelineDesc{.name = "play.accumulate"});
  b.accumulate->warm_up();
  return b;
}

runtime::Buffer make_accum(runtime::Device& device, std::uint32_t w, std::uint32_t h) {
  return runtime::Buffer(device, {.size = std::uint64_t{w} * h * 16,
                                  .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                  .name = "play.accum"});
}

graph::BufferHandle add_accumulate_pass(graph::RenderGraph& g, const runtime::ComputePipeline& p,
                                        const runtime::Buffer& accum, graph::BufferHandle hdr,
                                        std::uint32_t pixels, std::uint32_t count) {
  struct Data {
    graph::BufferHandle hdr, accum;
  };
  const graph::BufferHandle imported =
      g.import_buffer("play.accum", accum.handle(), {accum.size()}, {.initial = kAnyPriorUse});
  const gpu::PlayAccumulatePush push{pixels, count, 0u, 0u};
  const Data& data = g.add_pass<Data>(
      "play.accumulate", graph::PassKind::Compute,
      [&](graph::PassBuilder& b, Data& d) {
        d.hdr = b.write(hdr, graph::Access::StorageReadWrite);
        d.accum = b.write(imported, graph::Access::StorageReadWrite);
        b.side_effect();
      },
      [&p, push](graph::PassContext& ctx, const Data& d) {
        p.bind(ctx.cmd(), runtime::Bindings(p)
                              .buffer("hdr", ctx.buffer(d.hdr), 0, VK_WHOLE_SIZE)
                              .buffer("accum", ctx.buffer(d.accum), 0, VK_WHOLE_SIZE));
        p.push_constants(ctx.cmd(), push);
        p.dispatch_threads(ctx.cmd(), push.pixels);
      });
  return data.hdr;
}

Camera world_camera(World& world) {
  Camera camera;
  world.registry().view<const CameraComponent>().each(
      [&](const CameraComponent& c) { camera = c.camera; });
  return camera;
}

bool same_pose(const SnapshotCamera& a, const SnapshotCamera& b) {
  return a.view == b.view && a.projection == b.projection;
}

}  // namespace

PlayReport run_play(const PlayConfig& config) {
  PlayReport report;
  const std::shared_ptr<const Level> authored =
      config.loaded_level ? config.loaded_level
                          : std::make_shared<const Level>(load_level_argument(config.level));
  Level loaded = *authored;  // gets the play lights below

  runtime::DeviceOptions device_options{.selector = config.device};
  const auto glfw = runtime::enable_presentation(device_options);
  runtime::Device device(device_options);
  // No size asked for: one the device can hold at an interactive rate (lavapipe renders on the
  // CPU: 640x360 ran night_market at 0.9 fps).
  const bool cpu_device = device.info().type == "cpu";
  const std::uint32_t window_width = config.width > 0 ? config.width : cpu_device ? 320 : 1280;
  const std::uint32_t window_height = config.height > 0 ? config.height : cpu_device ? 180 : 720;
  runtime::Window window({.title = fmt::format("lantern - {} - F1 panel, right mouse + WASD fly, "
                                               "F flashlight, Space spawn light, Esc quit",
                                               config.level),
                          .width = window_width,
                          .height = window_height});
  runtime::WindowTarget target(device, window);
  const auto fb = window.framebuffer_size();
  std::uint32_t width = fb.width > 0 ? fb.width : window_width;
  std::uint32_t height = fb.height > 0 ? fb.height : window_height;
  DynamicResolution dynamic(config.dynamic_resolution);
  auto last_frame = Clock::now();
  bool have_last_frame = false;

  // Exposure: the log-average luminance of one headless frame of the level as authored.
  float exposure = 1.0f;
  {
    runtime::ShaderLibrary probe_shaders;
    lighting::OfflineRenderRequest probe;
    probe.width = std::min<std::uint32_t>(width, 320);
    probe.height = std::max<std::uint32_t>(1, probe.width * height / std::max(width, 1u));
    probe.seed = config.seed;
    exposure = lighting::auto_exposure(
        lighting::render_offline(device, probe_shaders, authored, probe).images.front());
  }
  const PlayLightSlots slots = add_play_lights(loaded, exposure);
  const auto level = std::make_shared<const Level>(std::move(loaded));

  ShaderReloader reloader(config.shader_source_dir.empty() ? ShaderReloader::default_source_dir()
                                                           : config.shader_source_dir,
                          runtime::ShaderLibrary::default_dir());
  reloader.poll(0.0);  // records the current mtimes

  PanelState panel;
  panel.level = config.level;
  panel.integrator = config.integrator.name;
  panel.preset = config.integrator.preset;
  if (panel.integrator == lighting::RestirIntegrator::kName)
    panel.restir =
        lighting::make_restir_settings(config.integrator.preset, config.integrator.settings);
  else
    panel.restir = lighting::restir_preset(config.integrator.preset);
  panel.denoise = lighting::make_denoise_settings(config.integrator.preset, config.integrator.denoise);
  bool show_panel = config.show_panel;

  RenderBundle bundle =
      build_bundle(device, reloader, level, config.integrator, width, height, config.seed);
  runtime::ShaderLibrary ui_shaders;
  PlayUi ui(device, ui_shaders, target.frames_in_flight());
  ui.warm_up();
  runtime::Buffer accum = make_accum(device, width, height);

  World world(level, {.threads = 1,
                      .seed = config.seed,
                      .fixed_dt = 1.0 / 60.0,
                      .aspect = static_cast<float>(width) / static_cast<float>(height)});
  enable_fly_camera(world);
  PlayLights lights(world, slots);

  lighting::FrameSession session(device, target, *bundle.renderer);
  session.set_timing_interval(kPlayTimingInterval);

  InputScript script = config.script;
  PlayInput before;
  std::uint32_t accumulated = 0;
  auto last_wall = Clock::now();
  log::info("play: {} at {}x{}, {} integrator, exposure {:.3g}; keys:\n{}", config.level, width,
            height, panel.integrator, exposure, play_keys_help());

  auto rebuild = [&](const lighting::IntegratorConfig& c, const char* why) {
    device.wait_idle();
    bundle = build_bundle(device, reloader, level, c, width, height, config.seed);
    session.set_renderer(*bundle.renderer);  // its first frame drops the graph's history
    accumulated = 0;
    ++report.rebuilds;
    log::info("play: {} ({} integrator)", why, c.name);
  };

  while (true) {
    window.poll_events();
    PlayInput input = input_from_window(window.input());
    script.apply(report.frames, input);
    if (input.quit || window.should_close() || input.key(GLFW_KEY_ESCAPE)) break;
    if (config.max_frames > 0 && report.frames >= config.max_frames) break;

    // Hot reload: recompile what changed; a new bundle from the new code, or keep the old one.
    if (const auto changed = reloader.poll(config.watch_interval_s); !changed.empty()) {
      const ReloadResult r = reloader.recompile(changed);
      if (!r.ok()) {
        ++report.reload_failures;
        report.last_reload_error = r.errors;
        panel.reload_error = r.errors;
        panel.reload_status = fmt::format("{} failed to compile; keeping the old pipelines",
                                          fmt::join(r.changed, ", "));
        log::warn("play: shader reload failed, keeping the old pipelines:\n{}", r.errors);
      } else if (!r.compiled.empty()) {
        try {
          rebuild(config_for(panel, config.integrator), "shaders reloaded");
          ++report.reloads_ok;
          panel.reload_error.clear();
          panel.reload_status = fmt::format("reloaded {}", fmt::join(r.compiled, ", "));
        } catch (const std::exception& error) {
          ++report.reload_failures;
          report.last_reload_error = error.what();
          panel.reload_error = error.what();
          panel.reload_status = "pipelines failed to build; keeping the old ones";
          // build_bundle threw before `bundle` was assigned: the old bundle is intact.
          log::warn("play: shader reload failed, keeping the old pipelines: {}", error.what());
        }
      }
    }

    if (window.minimized()) {
      ++report.skipped;
      window.wait_events(0.05);
      before = input;
      continue;
    }
    lighting::FrameTiming finished;
    const auto frame = session.begin_frame(&finished);
    if (!frame) {
      ++report.skipped;
      before = input;
      continue;
    }
    if (config.on_frame) config.on_frame(report.frames);

    // GPU times of the frame that last used this slot (its fence has been waited for).
    if (finished.gpu_valid) {
      for (const auto& [name, ms] : finished.passes) {
        push_sample(panel.pass_ms[name], static_cast<float>(ms));
      }
      push_sample(panel.frame_ms, static_cast<float>(finished.gpu_ms));
      report.frame_ms.push_back(finished.gpu_ms);
    }

    // The render size follows the window.
    const VkExtent2D extent = frame->render_extent;
    if (extent.width != width || extent.height != height) {
      device.wait_idle();
      width = extent.width;
      height = extent.height;
      bundle.renderer->resize(width, height);
      accum = make_accum(device, width, height);
      accumulated = 0;
      world.registry().ctx().get<WorldSettings>().aspect =
          static_cast<float>(width) / static_cast<float>(height);
      world.request_camera_cut();
    }
    // Dynamic resolution: the interval since the last rendered frame moves the internal size.
    const auto frame_start = Clock::now();
    if (have_last_frame) {
      const double interval =
          std::chrono::duration<double, std::milli>(frame_start - last_frame).count();
      report.interval_ms.push_back(interval);
      dynamic.update(interval);
    }
    last_frame = frame_start;
    have_last_frame = true;
    {
      const auto [iw, ih] = dynamic.internal_size(width, height);
      if (iw != bundle.renderer->width() || ih != bundle.renderer->height()) {
        device.wait_idle();  // the graph's per-size resources may still be in flight
        bundle.renderer->set_internal_size(iw, ih);
        accumulated = 0;
        if (report.frames > 0) ++report.resolution_changes;
      }
    }
    const std::uint32_t iw = bundle.renderer->width(), ih = bundle.renderer->height();
    if (report.frames == 0 || iw < report.min_internal_width) report.min_internal_width = iw;
    if (report.frames == 0 || ih < report.min_internal_height) report.min_internal_height = ih;
    report.max_internal_width = std::max(report.max_internal_width, iw);
    report.max_internal_height = std::max(report.max_internal_height, ih);

    const auto now = Clock::now();
    const float wall_dt = std::chrono::duration<float>(now - last_wall).count();
    last_wall = now;

    // ImGui first, so its mouse/keyboard capture is known for the camera.
    if (pressed(input, before, GLFW_KEY_F1)) show_panel = !show_panel;
    if (show_panel) {
      ui.new_frame(input, width, height, wall_dt);
      draw_panel(panel);
    }
    const bool keys_free = !(show_panel && ui.wants_keyboard());
    const bool mouse_free =
        !(show_panel && ui.wants_mouse()) || input.button(GLFW_MOUSE_BUTTON_RIGHT);
    auto key_pressed = [&](int key) { return keys_free && pressed(input, before, key); };

    // Integrator and ReSTIR settings.
    const std::span<const lighting::IntegratorEntry> entries = lighting::integrators();
    for (std::size_t i = 0; i < entries.size() && i < kIntegratorKeys; ++i) {
      if (key_pressed(GLFW_KEY_1 + static_cast<int>(i)) && panel.integrator != entries[i].name) {
        panel.integrator = entries[i].name;
        panel.rebuild = true;
      }
    }
    if (key_pressed(GLFW_KEY_V)) {
      // The views' rows follow their kRestirDebug* constants (restir_settings.cpp checks).
      const std::span<const lighting::RestirChoice> views = lighting::restir_debug_views();
      panel.restir.debug_view = views[(panel.restir.debug_view + 1) % views.size()].value;
      panel.settings_changed = true;
    }
    if (panel.rebuild) {
      panel.rebuild = false;
      panel.settings_changed = false;
      try {
        rebuild(config_for(panel, config.integrator), "integrator switched");
      } catch (const std::exception& error) {
        log::warn("play: integrator switch failed: {}", error.what());
        panel.reload_error = error.what();
      }
    }
    // The panel's ReSTIR knobs go to the running integrator when it is ReSTIR (otherwise they
    // wait in the panel for the next switch to it).
    if (std::exchange(panel.settings_changed, false) &&
        bundle.integrator->name == std::string_view(lighting::RestirIntegrator::kName)) {
      try {
        bundle.renderer->integrator().apply_settings(lighting::describe(panel.restir));
      } catch (const InputError& error) {
        log::warn("play: settings refused: {}", error.what());
        panel.reload_error = error.what();
      }
    }

    // Lights.
    if (key_pressed(GLFW_KEY_F) || std::exchange(panel.toggle_flashlight, false))
      lights.toggle_flashlight();
    if (key_pressed(GLFW_KEY_L) || std::exchange(panel.toggle_level_lights, false))
      lights.toggle_level_lights();
    if (key_pressed(GLFW_KEY_K) || std::exchange(panel.toggle_emissive, false))
      lights.toggle_emissive_surfaces();
    if (key_pressed(GLFW_KEY_SPACE) || std::exchange(panel.spawn_light, false)) {
      if (lights.spawn_light(bundle.renderer->scene()))
        log::info("play: light spawned at ({:.2f}, {:.2f}, {:.2f})", lights.last_spawn()->x,
                  lights.last_spawn()->y, lights.last_spawn()->z);
    }
    if (key_pressed(GLFW_KEY_C) || std::exchange(panel.clear_lights, false)) lights.clear_spawned();

    // Fly camera: right button (look) or any movement key takes manual control; P resumes.
    FlyCamera& fly = fly_camera(world);
    FlyCameraInput move;
    if (keys_free) {
      move.move.x = float(input.key(GLFW_KEY_D)) - float(input.key(GLFW_KEY_A));
      move.move.y = float(input.key(GLFW_KEY_E)) - float(input.key(GLFW_KEY_Q));
      move.move.z = float(input.key(GLFW_KEY_W)) - float(input.key(GLFW_KEY_S));
      move.boost = input.key(GLFW_KEY_LEFT_SHIFT) || input.key(GLFW_KEY_RIGHT_SHIFT) ? 4.0f : 1.0f;
    }
    const bool looking = mouse_free && input.button(GLFW_MOUSE_BUTTON_RIGHT);
    if (looking) {
      move.yaw = static_cast<float>(-input.cursor_dx) * kLookRadiansPerUnit;
      move.pitch = static_cast<float>(-input.cursor_dy) * kLookRadiansPerUnit;
    }
    if (mouse_free && input.scroll_y != 0.0)
      fly.speed = std::clamp(fly.speed * std::pow(1.25f, static_cast<float>(input.scroll_y)), 0.01f,
                             1000.0f);
    if (!fly.active && (looking || glm::length(move.move) > 0.0f)) {
      take_manual_control(world);
      fly.speed = std::max(0.05f, 0.25f * level_radius(*level));
      log::info("play: manual camera (P resumes the path)");
    }
    if ((key_pressed(GLFW_KEY_P) || std::exchange(panel.resume_path, false)) && fly.active)
      resume_camera_path(world);
    if (looking != window.cursor_captured()) window.capture_cursor(looking);
    move.dt = config.script.empty() ? std::clamp(wall_dt, 0.0f, 0.1f) : 0.0f;
    fly.input = move;

    const Camera camera_before = world_camera(world);
    const FrameSnapshot& snapshot = world.step();
    report.camera_travel += glm::length(world_camera(world).position - camera_before.position);
    if (fly.active) ++report.manual_frames;
    if (snapshot.camera_cut) ++report.camera_cuts;

    // The frame: the session's passes, accumulation between the HDR image and the output while
    // a progressive integrator holds still, the panel over the output.
    // The window shows the denoised image, except while a progressive integrator accumulates a
    // still view or a ReSTIR debug view is up (both want the raw image).
    const bool accumulate = bundle.integrator->progressive && panel.progressive;
    const bool debug_view = bundle.integrator->name == std::string(lighting::RestirIntegrator::kName) &&
                            panel.restir.debug_view != gpu::kRestirDebugNone;
    bundle.renderer->set_output(accumulate || debug_view ? lighting::FrameOutput::Raw
                                                         : lighting::FrameOutput::Denoised);
    bundle.renderer->set_denoise_settings(panel.denoise);
    lighting::FrameHooks hooks;
    hooks.exposure = exposure;
    if (bundle.integrator->progressive && panel.progressive) {
      hooks.hdr = [&](graph::RenderGraph& g, graph::BufferHandle hdr) {
        const auto& update = bundle.renderer->scene().last_update();
        const bool still = !snapshot.camera_cut &&
                           same_pose(snapshot.camera, snapshot.prev_camera) &&
                           update.moved_instances == 0 && !update.lights_changed;
        accumulated = still ? accumulated + 1 : 1;
        return add_accumulate_pass(g, *bundle.accumulate, accum, hdr, width * height, accumulated);
      };
    } else {
      accumulated = 0;
    }
    if (show_panel) {
      hooks.output = [&](graph::RenderGraph& g, graph::ImageHandle output,
                         const runtime::TargetFrame& f) {
        ++report.panel_frames;
        const graph::ImageHandle shown = ui.add_passes(g, output, width, height, f.slot);
        report.max_ui_triangles = std::max(report.max_ui_triangles, ui.last_triangles());
        return shown;
      };
    }
    session.render(*frame, snapshot, hooks);
    ++report.frames;

    // Panel state for the next frame.
    const float wall_ms = std::chrono::duration<float, std::milli>(Clock::now() - now).count();
    push_sample(panel.wall_ms, wall_ms);
    report.wall_ms.push_back(wall_ms);
    panel.width = width;
    panel.height = height;
    panel.internal_width = bundle.renderer->width();
    panel.internal_height = bundle.renderer->height();
    panel.target_ms = config.dynamic_resolution.target_ms;
    report.output_width = width;
    report.output_height = height;
    panel.accumulated = accumulated;
    panel.flashlight = lights.flashlight_on();
    panel.level_lights = lights.level_lights_on();
    panel.emissive = lights.emissive_on();
    panel.spawned = lights.spawned();
    panel.manual_camera = fly.active;
    panel.camera_speed = fly.speed;
    const glm::vec3 p = world_camera(world).position;
    panel.camera_position[0] = p.x;
    panel.camera_position[1] = p.y;
    panel.camera_position[2] = p.z;
    before = input;
  }
  if (show_panel) ui.end_frame_without_drawing();
  device.wait_idle();
  report.spawned_lights = lights.spawned();
  report.flashlight = lights.flashlight_on();
  report.integrator = bundle.integrator->name;
  report.integrator_settings = bundle.renderer->integrator().describe_settings();
  report.validation_errors = device.validation_errors();
  const auto median = [](const std::vector<double>& v) {
    return perf::percentile(std::span<const double>(v), 50.0);
  };
  log::info(
      "play: {} frames shown ({} skipped), median {:.2f} ms GPU / {:.2f} ms wall per frame, camera "
      "moved {:.2f} m, {} validation errors",
      report.frames, report.skipped, median(report.frame_ms), median(report.wall_ms),
      report.camera_travel, report.validation_errors);
  if (config.dynamic_resolution.target_ms > 0.0 && report.interval_ms.size() > 2 * kWarmUpFrames) {
    const std::vector<double> settled(report.interval_ms.begin() + kWarmUpFrames,
                                      report.interval_ms.end());
    const double m = median(settled);
    log::info("play: frame interval after {} warm-up frames: median {:.1f} ms for a {:.1f} ms "
              "target ({:+.0f}%), internal size {}x{}..{}x{} of {}x{}, {} changes",
              kWarmUpFrames, m, config.dynamic_resolution.target_ms,
              100.0 * (m / config.dynamic_resolution.target_ms - 1.0), report.min_internal_width,
              report.min_internal_height, report.max_internal_width, report.max_internal_height,
              report.output_width, report.output_height, report.resolution_changes);
  }
  if (device.validation_enabled() && device.validation_errors() > 0)
    throw RuntimeError(fmt::format("play: {} validation errors", device.validation_errors()));
  return report;
}

}  // namespace lantern::app
