// `lantern play [LEVEL]`: the level in a window. This round it is a progressive viewer: the
// baseline integrator renders the level's fixed camera frame after frame, the running mean is
// tonemapped on the host and shown through the window target (view.upload, target.present).
// Esc or closing the window quits; --frames N quits after N frames (scripts, tests).
#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include <memory>
#include <vector>

#include "apps/lantern/commands.h"
#include "engine/core/log.h"
#include "engine/level/level_loader.h"
#include "lighting/integrators/auto_exposure.h"
#include "lighting/integrators/offline_render.h"
#include "runtime/core/device.h"
#include "runtime/gpu/bindings.h"
#include "runtime/gpu/buffer.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/graph/graph_executor.h"
#include "runtime/graph/render_graph.h"
#include "runtime/target/window_target.h"
#include "runtime/window/presentation.h"
#include "runtime/window/window.h"
#include "shared/tonemap.h"

namespace lantern::app {
namespace {

struct PlayOptions {
  std::string level = "cornell_lights";
};

struct UploadPush {
  std::uint32_t size[2];
};

// Running mean of the frames so far, tonemapped to display-referred linear values in [0,1]
// (target.present does the sRGB encoding).
void write_display_pixels(const std::vector<double>& sum, std::uint32_t frames, float exposure,
                          float* out) {
  const double scale = exposure / static_cast<double>(frames);
  for (std::size_t i = 0; i < sum.size(); i += 4) {
    for (std::size_t c = 0; c < 3; ++c)
      out[i + c] = gpu::tonemap_filmic(static_cast<float>(sum[i + c] * scale));
    out[i + 3] = 1.0f;
  }
}

void play(const PlayOptions& play_options, const CommonOptions& common) {
  const auto [width, height] = parse_size(common.size);
  const auto level = std::make_shared<const Level>(load_level_argument(play_options.level));

  runtime::DeviceOptions device_options{.selector = common.device};
  const auto glfw = runtime::enable_presentation(device_options);
  runtime::Device device(device_options);
  runtime::Window window({.title = fmt::format("lantern - {}", play_options.level),
                          .width = width, .height = height});
  runtime::WindowTarget target(device, window, {.render_width = width, .render_height = height});
  runtime::ShaderLibrary shaders;
  runtime::ComputePipeline upload(device, shaders.load("view/view_upload.comp"),
                                  {.name = "view.upload"});
  upload.warm_up();
  runtime::graph::RenderGraph graph;
  runtime::graph::GraphExecutor executor(device);

  const VkDeviceSize bytes = VkDeviceSize{width} * height * 4 * sizeof(float);
  std::vector<runtime::Buffer> pixels;
  for (std::uint32_t i = 0; i < target.frames_in_flight(); ++i)
    pixels.emplace_back(device, runtime::BufferDesc{.size = bytes,
                                                    .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                                    .memory = runtime::MemoryUsage::Upload,
                                                    .name = fmt::format("view.pixels.{}", i)});

  std::vector<double> sum(std::size_t{width} * height * 4, 0.0);
  std::uint32_t frames = 0;
  float exposure = 1.0f;
  const std::uint32_t max_frames = common.frames > 0 ? static_cast<std::uint32_t>(common.frames) : 0;
  log::info("play: {} at {}x{}, baseline integrator, progressive (Esc quits)", play_options.level,
            width, height);
  while (!window.should_close() && !window.input().key_down(GLFW_KEY_ESCAPE) &&
         (max_frames == 0 || frames < max_frames)) {
    window.poll_events();
    const auto frame = target.begin_frame();
    if (!frame) continue;

    lighting::OfflineRenderRequest request{.width = width, .height = height, .frames = 1,
                                           .seed = common.seed + frames};
    const auto result = lighting::render_offline(device, shaders, *level, request);
    const runtime::ImageRGBA32F& image = result.images.front();
    if (frames == 0) exposure = lighting::auto_exposure(image);
    for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += image.pixels[i];
    ++frames;
    runtime::Buffer& staging = pixels[frame->slot];
    write_display_pixels(sum, frames, exposure, reinterpret_cast<float*>(staging.mapped()));

    graph.begin_frame();
    const auto output = target.import_output(graph, *frame);
    const auto source = graph.import_buffer(
        "view.pixels", staging.handle(), {.size = bytes},
        {.read_only = true, .initial = {VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_WRITE_BIT}});
    struct Data {
      runtime::graph::BufferHandle pixels;
      runtime::graph::ImageHandle image;
    };
    const Data& written = graph.add_pass<Data>(
        "view.upload", runtime::graph::PassKind::Compute,
        [&](runtime::graph::PassBuilder& b, Data& d) {
          d.pixels = source;
          b.read(source, runtime::graph::Access::StorageRead);
          d.image = b.write(output, runtime::graph::Access::StorageWrite);
        },
        [&upload, width, height](runtime::graph::PassContext& ctx, const Data& d) {
          upload.bind(ctx.cmd(), runtime::Bindings(upload)
                                     .buffer("Pixels", ctx.buffer(d.pixels), 0, VK_WHOLE_SIZE)
                                     .image_view("target", ctx.view(d.image),
                                                 VK_IMAGE_LAYOUT_GENERAL));
          upload.push_constants(ctx.cmd(), UploadPush{{width, height}});
          upload.dispatch_threads(ctx.cmd(), width, height);
        });
    target.add_delivery(graph, *frame, written.image);
    graph.bake(executor.compile_options());
    executor.record(graph, frame->cmd);
    graph.end_frame();
    target.end_frame(*frame);
  }
  device.wait_idle();
  log::info("play: {} frames shown; {} validation errors", frames, device.validation_errors());
  if (device.validation_enabled() && device.validation_errors() > 0)
    throw RuntimeError(fmt::format("play: {} validation errors", device.validation_errors()));
}

}  // namespace

void add_play_command(CLI::App& root, CommonOptions& options) {
  auto play_options = std::make_shared<PlayOptions>();
  auto* cmd = root.add_subcommand("play", "Show a level in a window (progressive viewer)");
  cmd->add_option("level", play_options->level, "Level: a .json/.gltf/.glb path or a name")
      ->capture_default_str();
  add_common_flags(*cmd, options);
  cmd->callback([play_options, &options] { play(*play_options, options); });
}

}  // namespace lantern::app
