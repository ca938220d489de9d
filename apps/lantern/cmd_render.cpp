// `lantern render LEVEL --integrator NAME (integrator_registry.h) [--frame K] [--frames N]
// [--spp N] [--average] [--static] [--output raw|denoised] [--render-scale S] --out PATH`
// (CLI.md): steps the level's world K frames, then renders N frames headless (objects, lights
// and camera animate unless --static) and writes them: one .exr/.png file when one image results,
// else a directory of frame_NNNN.exr. --preset and --set KEY=VALUE go to the integrator (an
// unknown key is an error).
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "apps/lantern/commands.h"
#include "engine/core/error.h"
#include "engine/core/log.h"
#include "engine/level/level_loader.h"
#include "lighting/integrators/auto_exposure.h"
#include "lighting/integrators/offline_render.h"
#include "runtime/core/device.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/image/image_io.h"

namespace lantern::app {
namespace {

struct RenderOptions {
  std::string level;
  std::string integrator;
  bool average = false;
  std::string out;
  float exposure = 0.0f;  // PNG only; 0 = automatic (log-average luminance to middle grey)
  std::uint32_t first_frame = 0;
  std::uint32_t spp = 0;
  bool still = false;  // --static: every frame renders the first rendered frame's snapshot
  std::string output;  // --output raw|denoised; empty: raw for EXR, denoised for PNG
  float render_scale = 1.0f;  // --render-scale: the denoised image's internal size / --size
};

// --output, or the default for the file type: EXR (and a directory of EXRs) raw, PNG denoised.
lighting::FrameOutput frame_output(const RenderOptions& o) {
  if (!o.output.empty()) return lighting::parse_frame_output(o.output);
  return std::filesystem::path(o.out).extension() == ".png" ? lighting::FrameOutput::Denoised
                                                           : lighting::FrameOutput::Raw;
}

// Whether --out names one image file (.exr/.png) or a directory; InputError for anything else
// and for one file when several images result.
bool out_is_file(const std::filesystem::path& out, std::size_t image_count) {
  const std::string ext = out.extension().string();
  if (ext.empty()) return false;
  if (ext != ".exr" && ext != ".png") {
    throw InputError(
        fmt::format("--out {}: expected a directory, a .exr or a .png file", out.string()));
  }
  if (image_count != 1) {
    throw InputError(fmt::format("--out {}: {} frames result; give a directory or --average",
                                 out.string(), image_count));
  }
  return true;
}

// The directory the output goes into must exist or be creatable, checked before rendering: the
// nearest existing ancestor must be a writable directory.
void require_writable_parent(const std::filesystem::path& out, bool file) {
  std::filesystem::path dir = file ? out.parent_path() : out;
  if (dir.empty()) dir = ".";
  std::filesystem::path probe = std::filesystem::absolute(dir);
  while (!std::filesystem::exists(probe) && probe.has_parent_path() &&
         probe != probe.parent_path()) {
    probe = probe.parent_path();
  }
  if (!std::filesystem::is_directory(probe)) {
    throw InputError(fmt::format("--out {}: {} is not a directory", out.string(), probe.string()));
  }
  if (access(probe.c_str(), W_OK) != 0) {
    throw InputError(fmt::format("--out {}: {} is not writable", out.string(), probe.string()));
  }
}

void write_images(const std::filesystem::path& out,
                  const std::vector<runtime::ImageRGBA32F>& images, float exposure) {
  if (out_is_file(out, images.size())) {
    if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
    const float e = exposure > 0.0f ? exposure : lighting::auto_exposure(images[0]);
    if (out.extension() == ".png") log::info("PNG exposure {:.4g}", e);
    runtime::write_image(out, images[0], e);
    return;
  }
  std::filesystem::create_directories(out);
  for (std::size_t i = 0; i < images.size(); ++i) {
    runtime::write_image(out / fmt::format("frame_{:04}.exr", i), images[i]);
  }
}

void run_render(const RenderOptions& o, const CommonOptions& common) {
  lighting::OfflineRenderRequest request;
  (void)lighting::find_integrator(o.integrator);  // an unknown name is refused first
  request.first_frame = o.first_frame;
  request.animate = !o.still;
  const auto [width, height] = parse_size(common.size);
  request.width = width;
  request.height = height;
  request.frames = common.frames > 0 ? static_cast<std::uint32_t>(common.frames) : 1u;
  request.average = o.average;
  request.seed = common.seed;
  request.output = frame_output(o);
  require_denoised_for_render_scale(o.render_scale, request.output,
                                    "add --output denoised, or write a .png");
  request.render_scale = o.render_scale;
  // Refuse a bad --out before any work.
  require_writable_parent(o.out, out_is_file(o.out, request.average ? 1u : request.frames));
  const auto level = std::make_shared<const Level>(load_level_argument(o.level));
  // The level's settings for this integrator, then --set (apps/lantern/commands.h).
  request.integrator = integrator_config(o.integrator, common, *level);
  request.integrator.spp = o.spp;
  lighting::validate_integrator_config(request.integrator);  // before any device work

  runtime::Device device({.selector = common.device});
  runtime::ShaderLibrary shaders;
  const lighting::OfflineRenderResult result =
      lighting::render_offline(device, shaders, level, request);
  write_images(o.out, result.images, o.exposure);
  log::info("{} {} frame(s) from frame {} at {}x{}{}: median {:.2f} ms/frame (GPU); wrote {} ({})",
            request.integrator.name, request.frames, request.first_frame, width, height,
            o.render_scale < 1.0f ? fmt::format(" (render scale {})", o.render_scale) : "",
            result.median_frame_ms(), o.out, lighting::frame_output_name(request.output));
  // Median GPU ms per pass, in the order of the first frame.
  if (!result.pass_ms.empty()) {
    std::string passes;
    for (const auto& [name, ms] : result.pass_ms.front()) {
      passes += fmt::format(" {} {:.2f}", name, result.median_pass_ms(name));
    }
    log::info("median pass ms:{}", passes);
  }
  std::vector<double> update = result.scene_update_ms;
  std::sort(update.begin(), update.end());
  if (!update.empty()) {
    log::info("scene update (CPU): median {:.2f} ms, max {:.2f} ms", update[update.size() / 2],
              update.back());
  }
  if (result.scene_updates.size() > 1) {
    // The last frame's breakdown (frame 0 only applies the first snapshot).
    const lighting::SceneUpdateStats& s = result.scene_updates.back();
    log::info(
        "last scene update: {:.2f} ms (instances {:.2f}: {} moved, TLAS {}; lights {:.2f}: {} "
        "instances / {} triangles re-extracted, alias {}), {} bytes uploaded",
        s.cpu_ms, s.instance_ms, s.moved_instances, s.tlas_rebuilt ? "rebuilt" : "kept", s.light_ms,
        s.reextracted_instances, s.reextracted_triangles, s.alias_rebuilt ? "rebuilt" : "kept",
        s.upload_bytes);
  }
  if (device.validation_enabled() && device.validation_errors() > 0) {
    throw RuntimeError(fmt::format("{} Vulkan validation error(s)", device.validation_errors()));
  }
}

}  // namespace

void add_render_command(CLI::App& root, CommonOptions& options) {
  auto opts = std::make_shared<RenderOptions>();
  auto* cmd = root.add_subcommand("render", "Render frames of a level headless to EXR/PNG");
  add_common_flags(*cmd, options);
  cmd->add_option("LEVEL", opts->level,
                  "Level: a .json/.gltf/.glb file or a name under content/levels/")
      ->required();
  add_integrator_option(*cmd, opts->integrator)->required();
  cmd->add_flag("--average", opts->average, "Write the mean of the frames as one image");
  cmd->add_option("--frame", opts->first_frame,
                  "Step the world K frames before the first rendered frame");
  cmd->add_option("--spp", opts->spp, "Samples per pixel per frame (reference integrator)");
  cmd->add_flag("--static", opts->still,
                "Render every frame from the first rendered frame's snapshot (no animation)");
  cmd->add_option("--out", opts->out, "Output directory, or one .exr/.png file")->required();
  cmd->add_option("--output", opts->output,
                  "raw (the integrator's unbiased image) or denoised; default raw for EXR, "
                  "denoised for PNG")
      ->check(CLI::IsMember({"raw", "denoised"}));
  add_render_scale_option(*cmd, opts->render_scale,
                          "Internal size of the denoised image as a fraction of --size "
                          "(upscale.temporal reconstructs it at --size, as play's dynamic "
                          "resolution does); needs the denoised output");
  cmd->add_option("--exposure", opts->exposure, "PNG exposure multiplier (default: automatic)")
      ->check(CLI::Range(1e-6f, 1e6f));
  cmd->callback([opts, &options] { run_render(*opts, options); });
}

}  // namespace lantern::app
