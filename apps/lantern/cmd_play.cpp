// `lantern play [LEVEL]`: the level running in a window. A World steps the level every frame
// (moving objects, animated lights, the camera path) and a FrameRenderer renders each snapshot
// with the baseline integrator (1 sample per pixel per frame, no accumulation); frame.output
// tonemaps it (exposure from one headless frame at start-up, filmic curve) into the window
// target, which presents it (target.present). Two frames in flight.
// Esc or closing the window quits; --frames N quits after N frames (scripts, tests).
#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include <memory>

#include "apps/lantern/commands.h"
#include "engine/core/error.h"
#include "engine/core/log.h"
#include "engine/level/level_loader.h"
#include "engine/world/world.h"
#include "lighting/frame/frame_renderer.h"
#include "lighting/integrators/auto_exposure.h"
#include "lighting/integrators/integrator_factory.h"
#include "lighting/integrators/offline_render.h"
#include "runtime/core/device.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/graph/graph_executor.h"
#include "runtime/graph/render_graph.h"
#include "runtime/target/window_target.h"
#include "runtime/window/presentation.h"
#include "runtime/window/window.h"

namespace lantern::app {
namespace {

struct PlayOptions {
  std::string level = "cornell_lights";
};

void play(const PlayOptions& play_options, const CommonOptions& common) {
  const auto [width, height] = parse_size(common.size);
  const auto level = std::make_shared<const Level>(load_level_argument(play_options.level));

  runtime::DeviceOptions device_options{.selector = common.device};
  const auto glfw = runtime::enable_presentation(device_options);
  runtime::Device device(device_options);
  runtime::Window window(
      {.title = fmt::format("lantern - {}", play_options.level), .width = width, .height = height});
  runtime::WindowTarget target(device, window, {.render_width = width, .render_height = height});
  runtime::ShaderLibrary shaders;

  // Exposure: the log-average luminance of one headless frame of the start of the level.
  lighting::OfflineRenderRequest probe;
  probe.width = width;
  probe.height = height;
  probe.seed = common.seed;
  const float exposure = lighting::auto_exposure(
      lighting::render_offline(device, shaders, level, probe).images.front());

  const lighting::IntegratorConfig config{.kind = lighting::IntegratorKind::Baseline};
  lighting::FrameRenderer renderer(device, shaders, level,
                                   lighting::make_integrator(device, shaders, config), width,
                                   height, common.seed);
  renderer.warm_up();
  World world(level, {.threads = 1,
                      .seed = common.seed,
                      .fixed_dt = 1.0 / 60.0,
                      .aspect = static_cast<float>(width) / static_cast<float>(height)});
  runtime::graph::RenderGraph graph;
  runtime::graph::GraphExecutor executor(device);

  std::uint32_t frames = 0;
  const std::uint32_t max_frames =
      common.frames > 0 ? static_cast<std::uint32_t>(common.frames) : 0;
  log::info("play: {} at {}x{}, baseline integrator, exposure {:.3g} (Esc quits)",
            play_options.level, width, height, exposure);
  while (!window.should_close() && !window.input().key_down(GLFW_KEY_ESCAPE) &&
         (max_frames == 0 || frames < max_frames)) {
    window.poll_events();
    const auto frame = target.begin_frame();
    if (!frame) continue;
    const FrameSnapshot& snapshot = world.step();
    graph.begin_frame();
    const runtime::graph::BufferHandle hdr = renderer.add_frame(graph, snapshot);
    const runtime::graph::ImageHandle output =
        renderer.add_output_pass(graph, hdr, target.import_output(graph, *frame), exposure);
    target.add_delivery(graph, *frame, output);
    graph.bake(executor.compile_options());
    executor.record(graph, frame->cmd);
    graph.end_frame();
    target.end_frame(*frame);
    ++frames;
  }
  device.wait_idle();
  log::info("play: {} frames shown; {} validation errors", frames, device.validation_errors());
  if (device.validation_enabled() && device.validation_errors() > 0)
    throw RuntimeError(fmt::format("play: {} validation errors", device.validation_errors()));
}

}  // namespace

void add_play_command(CLI::App& root, CommonOptions& options) {
  auto play_options = std::make_shared<PlayOptions>();
  auto* cmd = root.add_subcommand("play", "Show a level running in a window");
  cmd->add_option("level", play_options->level, "Level: a .json/.gltf/.glb path or a name")
      ->capture_default_str();
  add_common_flags(*cmd, options);
  cmd->callback([play_options, &options] { play(*play_options, options); });
}

}  // namespace lantern::app
