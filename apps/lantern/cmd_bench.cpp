// `lantern bench LEVEL [--integrator I] [--frames N] [--warmup N] [--json FILE] [--trace FILE]
// [--budget FILE]` (CLI.md): runs the level's path headless, warm-up frames first, then N timed
// frames; prints per-pass and frame statistics (median, p95, p99, max), writes them as JSON, a
// Chrome trace (CPU systems and GPU passes per frame), and checks a budget file (exit 3 naming
// every pass over budget). A calibration workload is timed in the same run, interleaved with
// the frames, so budgets can be relative to it (engine/perf/budget.h). `--startup` prints where
// the time to the first frame goes (level load, device, scene build and BVH, uploads and
// pipeline objects, pipeline JIT warm-up, first frame).
#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "apps/lantern/commands.h"
#include "engine/core/error.h"
#include "engine/core/log.h"
#include "engine/level/level_loader.h"
#include "engine/perf/budget.h"
#include "engine/perf/chrome_trace.h"
#include "engine/perf/statistics.h"
#include "engine/world/world.h"
#include "lighting/bvh/scene_bvh.h"
#include "lighting/frame/frame_renderer.h"
#include "lighting/frame/headless_session.h"
#include "lighting/integrators/integrator_registry.h"
#include "lighting/scene/gpu_scene.h"
#include "lighting/scene/scene_data.h"
#include "lighting/visibility/host_visibility.h"
#include "runtime/core/device.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/perf/calibration_workload.h"

namespace lantern::app {
namespace {

using Clock = std::chrono::steady_clock;

struct BenchOptions {
  std::string level;
  std::string integrator = "restir";
  int warmup = 10;
  std::string json;
  std::string trace;
  std::string budget;
  bool startup = false;
  std::string output = "raw";  // --output raw|denoised: time the denoise.* chain too
  float render_scale = 1.0f;   // --render-scale: internal size / --size (upscale.temporal)
};

// Calibration runs: one before the frames, then one every kCalibrationEvery frames.
constexpr int kCalibrationEvery = 8;

double us_between(Clock::time_point origin, Clock::time_point t) {
  return std::chrono::duration<double, std::micro>(t - origin).count();
}

double ms_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// Time to the first frame, step by step, in the order the bench runs them. The parts of the
// session's construction are measured again after the frames, each alone on the loaded level and
// the same device (so with warm in-process caches): the GPU scene (build_scene_data, of which
// the BVH, then uploads), the integrator's pipelines, the world.
struct StartupTimes {
  double level_ms = 0.0, device_ms = 0.0, calibration_ms = 0.0, session_ms = 0.0, warm_up_ms = 0.0,
         first_frame_ms = 0.0;
  double scene_build_ms = 0.0, bvh_ms = 0.0, gpu_scene_ms = 0.0, integrator_ms = 0.0,
         world_ms = 0.0;
  double total_ms() const {  // calibration is the bench's own: not part of a game's start-up
    return level_ms + device_ms + session_ms + warm_up_ms + first_frame_ms;
  }
};

void measure_session_parts(runtime::Device& device, runtime::ShaderLibrary& shaders,
                           const std::shared_ptr<const Level>& level_ptr,
                           const lighting::IntegratorConfig& config,
                           const lighting::SessionOptions& options, StartupTimes& t) {
  const Level& level = *level_ptr;
  Clock::time_point start = Clock::now();
  const std::unique_ptr<lighting::Integrator> integrator =
      lighting::make_integrator(device, shaders, config);
  t.integrator_ms = ms_between(start, Clock::now());
  start = Clock::now();
  { const lighting::GpuScene scene(device, level_ptr, integrator->visibility()); }
  t.gpu_scene_ms = ms_between(start, Clock::now());
  start = Clock::now();
  {
    const World world(level_ptr, {.threads = options.world_threads,
                                  .seed = options.seed,
                                  .fixed_dt = options.fixed_dt,
                                  .aspect = static_cast<float>(options.width) /
                                            static_cast<float>(options.height)});
  }
  t.world_ms = ms_between(start, Clock::now());
  const Clock::time_point a = Clock::now();
  (void)lighting::build_scene_data(level);
  const Clock::time_point b = Clock::now();
  lighting::SceneBvh bvh;
  std::vector<lighting::BvhInstanceDesc> descs;
  for (const Mesh& mesh : level.meshes)
    bvh.add_mesh(lighting::MeshBvh(mesh.positions, mesh.indices));
  for (std::size_t i = 0; i < level.instances.size(); ++i)
    descs.push_back(
        {level.instances[i].mesh, level.instances[i].world, static_cast<std::uint32_t>(i)});
  bvh.set_instances(descs);
  t.scene_build_ms = ms_between(a, b);
  t.bvh_ms = ms_between(b, Clock::now());
}

void print_startup(const StartupTimes& t) {
  const double rest = t.session_ms - t.gpu_scene_ms - t.integrator_ms - t.world_ms;
  std::printf("start-up (wall ms, in order):\n");
  std::printf("  %-46s %9.1f\n", "level load (parse + generators)", t.level_ms);
  std::printf("  %-46s %9.1f\n", "device (instance, device, pipeline cache)", t.device_ms);
  std::printf("  %-46s %9.1f\n", "session (scene, G-buffer, integrator, world)", t.session_ms);
  std::printf("  %-46s %9.1f\n", "  GPU scene*", t.gpu_scene_ms);
  std::printf("  %-46s %9.1f\n", "    scene build (build_scene_data)*", t.scene_build_ms);
  std::printf("  %-46s %9.1f\n", "      of which BVH (all BLASes + TLAS)*", t.bvh_ms);
  std::printf("  %-46s %9.1f\n", "    uploads (GPU scene - scene build)*",
              t.gpu_scene_ms - t.scene_build_ms);
  std::printf("  %-46s %9.1f\n", "  integrator pipeline objects*", t.integrator_ms);
  std::printf("  %-46s %9.1f\n", "  world (ECS, systems)*", t.world_ms);
  std::printf("  %-46s %9.1f\n", "  rest (G-buffer, output, target; session - *)", rest);
  std::printf("  %-46s %9.1f\n", "pipeline warm-up (lavapipe JIT)", t.warm_up_ms);
  std::printf("  %-46s %9.1f\n", "first frame (step + render, wall)", t.first_frame_ms);
  std::printf("  %-46s %9.1f\n", "first frame ready", t.total_ms());
  std::printf(
      "  (bench only, not counted: calibration workload %.1f ms; * measured again after "
      "the frames, each alone)\n",
      t.calibration_ms);
}

nlohmann::json summary_json(const perf::Summary& s) {
  return {{"median", s.median}, {"p95", s.p95}, {"p99", s.p99}, {"max", s.max}};
}

// Writes `text` to `path` through a temporary file (nothing half-written on failure).
void write_text_atomic(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(fmt::format("{}: cannot be written", path));
    out << text;
    if (!out.flush()) throw RuntimeError(fmt::format("{}: write failed", path));
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw RuntimeError(fmt::format("{}: cannot be written", path));
  }
}

void run_bench(const BenchOptions& o, const CommonOptions& common) {
  const auto [width, height] = parse_size(common.size);
  const int frames = common.frames > 0 ? common.frames : 60;
  if (o.warmup < 0 || o.warmup > 100000) {
    throw InputError(fmt::format("--warmup {}: expected 0..100000", o.warmup));
  }
  if (o.startup && o.warmup == 0) {
    throw InputError("--startup times the first warm-up frame: use --warmup 1 or more");
  }
  // Refuse a bad budget before any work.
  std::optional<perf::Budget> budget;
  if (!o.budget.empty()) budget = perf::load_budget(o.budget);
  StartupTimes startup;
  Clock::time_point mark = Clock::now();
  const auto lap = [&mark] {
    const Clock::time_point now = Clock::now();
    const double ms = ms_between(mark, now);
    mark = now;
    return ms;
  };
  const auto level = std::make_shared<const Level>(load_level_argument(o.level));
  const lighting::IntegratorConfig config = integrator_config(o.integrator, common, *level);
  startup.level_ms = lap();

  runtime::Device device({.selector = common.device});
  runtime::ShaderLibrary shaders;
  startup.device_ms = lap();
  runtime::CalibrationWorkload calibration(device, shaders);
  startup.calibration_ms = lap();
  const lighting::SessionOptions session_options{.integrator = config,
                                                 .width = width,
                                                 .height = height,
                                                 .seed = common.seed,
                                                 .output = lighting::parse_frame_output(o.output),
                                                 .render_scale = o.render_scale};
  lighting::HeadlessSession session(device, shaders, level, session_options);
  startup.session_ms = lap();
  session.warm_up();
  startup.warm_up_ms = lap();
  const std::string integrator = config.name;
  const lighting::VisibilityChoice visibility =
      lighting::choose_visibility(device.info(), config.visibility);
  log::info("bench {} {} {} at {}x{}: {} warm-up + {} frames on {}, visibility {} ({})",
            level->name, integrator, common.preset, width, height, o.warmup, frames,
            device.info().name, lighting::visibility_backend_name(visibility.backend),
            visibility.why);

  for (int k = 0; k < o.warmup; ++k) {
    session.render(session.step_world());
    if (k == 0) startup.first_frame_ms = lap();
  }

  std::vector<double> calibration_ms = {calibration.run_ms()};
  std::vector<double> frame_ms, wall_ms, update_ms;
  // Per frame, the sum of the denoise.* and of the upscale.* passes (à-trous runs several
  // passes of one name; `passes` summarises each instance).
  std::vector<double> denoise_ms, upscale_ms;
  // Host visibility: the shadow rays visibility.host traced per frame (pixels without a ray —
  // sky, no sample, a pick that lights nothing — trace none).
  std::vector<double> host_rays;
  // ... and the closest-hit rays visibility.host_closest traced (restir.initial's BSDF
  // candidates, where the settings draw them).
  std::vector<double> host_closest_rays;
  const lighting::HostVisibility* host = session.renderer().scene().host_visibility();
  std::map<std::string, std::vector<double>> pass_ms, system_ms;
  std::vector<std::string> pass_order;
  perf::ChromeTrace trace;
  const int cpu_track = trace.track("CPU: world systems");
  const int host_track = trace.track("CPU: frame");
  const int gpu_track = trace.track("GPU passes");
  const Clock::time_point origin = Clock::now();
  for (int k = 0; k < frames; ++k) {
    const Clock::time_point step_start = Clock::now();
    const FrameSnapshot& snapshot = session.step_world();
    const Clock::time_point render_start = Clock::now();
    const lighting::FrameTiming t = session.render(snapshot);
    frame_ms.push_back(t.gpu_ms);
    wall_ms.push_back(t.wall_ms);
    update_ms.push_back(t.scene_update_ms);
    double denoise = 0.0, upscale = 0.0;
    for (const auto& [name, ms] : t.passes) {
      if (!pass_ms.contains(name)) pass_order.push_back(name);
      pass_ms[name].push_back(ms);
      if (name.rfind("denoise.", 0) == 0) denoise += ms;
      if (name.rfind("upscale.", 0) == 0) upscale += ms;
    }
    denoise_ms.push_back(denoise);
    upscale_ms.push_back(upscale);
    if (host != nullptr) {
      host_rays.push_back(static_cast<double>(host->last_traced()));
      host_closest_rays.push_back(static_cast<double>(host->last_closest_traced()));
    }
    for (const auto& [name, ms] : t.systems) system_ms[name].push_back(ms);

    // Trace: systems laid out in run order inside the step (exact with one worker thread), the
    // frame's host time, and the GPU passes back to back from the submission (GPU timestamps give
    // durations; the passes of one frame run in order on one queue).
    double at = us_between(origin, step_start);
    trace.event(host_track, "world.step", at, t.step_ms * 1000.0);
    for (const auto& [name, ms] : t.systems) {
      trace.event(cpu_track, name, at, ms * 1000.0, "cpu");
      at += ms * 1000.0;
    }
    const double render_at = us_between(origin, render_start);
    trace.event(host_track, fmt::format("frame {}", k), render_at, t.wall_ms * 1000.0);
    at = render_at;
    for (const auto& [name, ms] : t.passes) {
      trace.event(gpu_track, name, at, ms * 1000.0, "gpu");
      at += ms * 1000.0;
    }
    if ((k + 1) % kCalibrationEvery == 0) calibration_ms.push_back(calibration.run_ms());
  }

  perf::BenchMeasurement m;
  m.level = level->name;
  m.size = {width, height};
  m.integrator = integrator;
  m.preset = common.preset;
  m.device = device.info().name;
  m.calibration_ms = perf::summarize(calibration_ms).median;
  m.frame = perf::summarize(frame_ms);
  for (const auto& [name, values] : pass_ms) m.passes[name] = perf::summarize(values);
  const perf::Summary wall = perf::summarize(wall_ms);

  // Rays per second: pixels over the G-buffer stages' time (primary visibility, rasterised or
  // traced by the host, with the resolve), and the integrator's declared shadow rays over the time
  // of the passes that trace them. The host G-buffer's own rate (its traversal alone, what
  // visibility_bench's Embree anchor measures) comes beside.
  const double pixels = static_cast<double>(width) * height;
  double primary_rps = 0.0, shadow_rps = 0.0;
  double gbuffer_ms = 0.0;  // every G-buffer stage: gbuffer, gbuffer.draws, .cull, .resolve
  for (const auto& [name, s] : m.passes) {
    if (name == "gbuffer" || name.rfind("gbuffer.", 0) == 0) gbuffer_ms += s.median;
  }
  if (gbuffer_ms > 0.0) primary_rps = pixels / (gbuffer_ms * 1e-3);
  const bool host_gbuffer = m.passes.contains("gbuffer.host");
  double primary_host_rps = 0.0;
  if (host_gbuffer && m.passes["gbuffer.host"].median > 0.0)
    primary_host_rps = pixels / (m.passes["gbuffer.host"].median * 1e-3);
  double shadow_rays = 0.0, shadow_ms = 0.0;
  for (const auto& [pass, per_pixel] : session.renderer().integrator().shadow_rays_per_pixel()) {
    if (auto it = m.passes.find(pass); it != m.passes.end()) {
      shadow_rays += per_pixel * pixels;
      shadow_ms += it->second.median;
    }
  }
  if (shadow_ms > 0.0) shadow_rps = shadow_rays / (shadow_ms * 1e-3);

  std::printf("%-24s %9s %9s %9s %9s\n", "pass (GPU ms)", "median", "p95", "p99", "max");
  for (const std::string& name : pass_order) {
    const perf::Summary& s = m.passes[name];
    std::printf("%-24s %9.3f %9.3f %9.3f %9.3f\n", name.c_str(), s.median, s.p95, s.p99, s.max);
  }
  std::printf("%-24s %9.3f %9.3f %9.3f %9.3f\n", "frame (GPU)", m.frame.median, m.frame.p95,
              m.frame.p99, m.frame.max);
  std::printf("%-24s %9.3f %9.3f %9.3f %9.3f\n", "frame (wall)", wall.median, wall.p95, wall.p99,
              wall.max);
  if (perf::summarize(denoise_ms).median > 0.0 || perf::summarize(upscale_ms).median > 0.0) {
    const double dn = perf::summarize(denoise_ms).median, up = perf::summarize(upscale_ms).median;
    std::printf("denoise %.3f ms + upscale %.3f ms per frame = %.1f%% of the frame (internal %ux%u)\n",
                dn, up, m.frame.median > 0.0 ? 100.0 * (dn + up) / m.frame.median : 0.0,
                session.renderer().width(), session.renderer().height());
  }
  std::printf("calibration %.3f ms (median of %zu); frame = %.2fx calibration\n", m.calibration_ms,
              calibration_ms.size(), m.frame.median / m.calibration_ms);
  std::printf("rays/s: primary %.3g (%s), shadow %.3g (visibility %s)\n", primary_rps,
              host_gbuffer ? "G-buffer traced by the host + resolve" : "G-buffer raster + resolve",
              shadow_rps,
              std::string(lighting::visibility_backend_name(visibility.backend)).c_str());
  if (host_gbuffer) {
    std::printf("host G-buffer: %.3g primary rays/s in gbuffer.host\n", primary_host_rps);
  }
  // The host's real throughput: rays it traced over visibility.host's time (the line above
  // counts one ray per pixel, as for the GPU backends).
  // Median rays per frame and rays per second of a host pass, where the frame ran it.
  struct HostRate {
    double rays_per_frame = 0.0;
    double rays_per_second = 0.0;
  };
  const auto host_rate = [&](const char* pass, const std::vector<double>& rays) {
    HostRate r;
    if (host == nullptr || !m.passes.contains(pass)) return r;
    r.rays_per_frame = perf::summarize(rays).median;
    const double ms = m.passes[pass].median;
    if (ms > 0.0) r.rays_per_second = r.rays_per_frame / (ms * 1e-3);
    return r;
  };
  const HostRate shadow_host = host_rate("visibility.host", host_rays);
  if (m.passes.contains("visibility.host")) {
    std::printf("host visibility: %.0f shadow rays traced per frame (%.0f%% of pixels), %.3g rays/s "
                "in visibility.host\n",
                shadow_host.rays_per_frame, 100.0 * shadow_host.rays_per_frame / pixels,
                shadow_host.rays_per_second);
  }
  const HostRate closest_host = host_rate("visibility.host_closest", host_closest_rays);
  if (m.passes.contains("visibility.host_closest")) {
    std::printf("host closest hits: %.0f BSDF candidate rays traced per frame (%.2f per pixel), "
                "%.3g rays/s in visibility.host_closest\n",
                closest_host.rays_per_frame, closest_host.rays_per_frame / pixels,
                closest_host.rays_per_second);
  }

  if (o.startup) {
    measure_session_parts(device, shaders, level, config, session_options, startup);
    print_startup(startup);
  }

  if (!o.json.empty()) {
    nlohmann::json passes = nlohmann::json::object();
    for (const auto& [name, s] : m.passes) passes[name] = summary_json(s);
    nlohmann::json systems = nlohmann::json::object();
    for (const auto& [name, values] : system_ms) {
      systems[name] = {{"median", perf::summarize(values).median}};
    }
    const nlohmann::json j = {
        {"level", level->name},
        {"integrator", integrator},
        {"preset", common.preset},
        {"settings", config.settings},
        {"output", o.output},
        {"render_scale", o.render_scale},
        {"internal_size", {session.renderer().width(), session.renderer().height()}},
        {"size", {width, height}},
        {"device", device.info().name},
        {"visibility", lighting::visibility_backend_name(visibility.backend)},
        {"visibility_why", visibility.why},
        // What ReSTIR's presampling tiles and local lists follow (RestirSettings::light_spread).
        {"light_spread", session.renderer().scene().data().light_spread.spread},
        {"frames", frames},
        {"warmup", o.warmup},
        {"seed", common.seed},
        {"frame_ms", summary_json(m.frame)},
        {"denoise_ms", perf::summarize(denoise_ms).median},
        {"upscale_ms", perf::summarize(upscale_ms).median},
        {"frame_wall_ms", summary_json(wall)},
        {"scene_update_ms", summary_json(perf::summarize(update_ms))},
        {"passes", passes},
        {"cpu_systems_ms", systems},
        {"calibration_ms", m.calibration_ms},
        {"rays_per_second",
         {{"primary", primary_rps}, {"primary_host", primary_host_rps}, {"shadow", shadow_rps}}},
        {"host_visibility",
         {{"rays_per_frame", shadow_host.rays_per_frame},
          {"rays_per_second", shadow_host.rays_per_second}}},
        {"host_closest_hits",
         {{"rays_per_frame", closest_host.rays_per_frame},
          {"rays_per_second", closest_host.rays_per_second}}},
    };
    nlohmann::json out = j;
    if (o.startup) {
      out["startup_ms"] = {{"level", startup.level_ms},
                           {"device", startup.device_ms},
                           {"session", startup.session_ms},
                           {"gpu_scene", startup.gpu_scene_ms},
                           {"scene_build", startup.scene_build_ms},
                           {"bvh", startup.bvh_ms},
                           {"integrator", startup.integrator_ms},
                           {"world", startup.world_ms},
                           {"warm_up", startup.warm_up_ms},
                           {"first_frame", startup.first_frame_ms},
                           {"total", startup.total_ms()}};
    }
    write_text_atomic(o.json, out.dump(2) + "\n");
  }
  if (!o.trace.empty()) trace.write(o.trace);
  if (device.validation_enabled() && device.validation_errors() > 0) {
    throw RuntimeError(fmt::format("{} Vulkan validation error(s)", device.validation_errors()));
  }
  if (budget) {
    const perf::BudgetResult result = perf::check_budget(*budget, m);
    std::printf("budget %s:\n", o.budget.c_str());
    for (const std::string& line : result.checked) std::printf("  %s\n", line.c_str());
    if (!result.passed()) {
      std::string names;
      for (const perf::BudgetViolation& v : result.violations) {
        names += fmt::format("{}{} ({:.3f} > {:.3f} {})", names.empty() ? "" : ", ", v.what,
                             v.measured, v.limit, v.unit);
      }
      throw BudgetExceeded(fmt::format("over budget: {}", names));
    }
  }
}

}  // namespace

void add_bench_command(CLI::App& root, CommonOptions& options) {
  auto opts = std::make_shared<BenchOptions>();
  auto* cmd = root.add_subcommand(
      "bench", "Frame-time benchmark along the level's path (exit 3 when over budget)");
  add_common_flags(*cmd, options);
  cmd->add_option("LEVEL", opts->level,
                  "Level: a .json/.gltf/.glb file or a name under content/levels/")
      ->required();
  add_integrator_option(*cmd, opts->integrator)->capture_default_str();
  cmd->add_option("--warmup", opts->warmup, "Frames rendered before timing")
      ->capture_default_str();
  cmd->add_option("--output", opts->output,
                  "raw (the integrator's image) or denoised (adds the denoise.* passes)")
      ->check(CLI::IsMember({"raw", "denoised"}))
      ->capture_default_str();
  add_render_scale_option(*cmd, opts->render_scale,
                          "Internal size as a fraction of --size; below 1 upscale.temporal "
                          "reconstructs");
  cmd->add_option("--json", opts->json, "Write the statistics as JSON to FILE");
  cmd->add_option("--trace", opts->trace,
                  "Write a Chrome trace (chrome://tracing, ui.perfetto.dev) to FILE");
  cmd->add_flag("--startup", opts->startup,
                "Print the time to the first frame step by step (level, device, scene and BVH, "
                "pipelines, first frame)");
  cmd->add_option("--budget", opts->budget,
                  "Check a budget file (see docs/budgets.md); exit 3 when over budget");
  cmd->callback([opts, &options] { run_bench(*opts, options); });
}

}  // namespace lantern::app
