// `lantern capture LEVEL [--path NAME] --frames N --out DIR [--format exr|png] [--video FILE.mp4]
// [--output raw|denoised] [--render-scale S]` (CLI.md): a scripted flythrough with a fixed time
// step — deterministic, the same seed gives the same files — written as frame_NNNN.exr/png,
// timings.csv (GPU ms per pass per frame) and capture.json (level, settings, device, versions);
// --video encodes the frames with ffmpeg. Files are written into a staging directory and moved
// into DIR only when everything succeeded.
#include <fmt/format.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "apps/lantern/commands.h"
#include "apps/lantern/progress.h"
#include "engine/core/error.h"
#include "engine/core/log.h"
#include "engine/level/level_loader.h"
#include "engine/world/world.h"
#include "lighting/denoise/denoise_settings.h"
#include "lighting/frame/headless_session.h"
#include "lighting/integrators/auto_exposure.h"
#include "runtime/core/device.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/image/image_io.h"

namespace lantern::app {
namespace {

namespace fs = std::filesystem;

struct CaptureOptions {
  std::string level;
  std::string integrator = "restir";
  std::string path;
  std::string out;
  std::string format = "exr";
  std::string video;
  float exposure = 0.0f;  // PNG/video: 0 = automatic from the first frame, then fixed
  std::string output;     // --output raw|denoised; empty: raw for EXR frames, denoised for PNG/video
  float render_scale = 1.0f;  // --render-scale: the denoised frames' internal size / --size
};

bool have_ffmpeg() { return std::system("command -v ffmpeg >/dev/null 2>&1") == 0; }

// Removes the staging directory unless the capture completed.
struct StagingDir {
  fs::path path;
  bool keep = false;
  ~StagingDir() {
    std::error_code ec;
    if (!keep) fs::remove_all(path, ec);
  }
};

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// timings.csv's columns of one frame: one per pass instance, a pass that runs several times a
// frame (the à-trous steps) as NAME, NAME#2, ... in the order it ran.
std::vector<std::pair<std::string, double>> pass_columns(
    const std::vector<std::pair<std::string, double>>& passes) {
  std::vector<std::pair<std::string, double>> out;
  std::map<std::string, int> seen;
  for (const auto& [name, ms] : passes) {
    const int n = ++seen[name];
    out.emplace_back(n == 1 ? name : fmt::format("{}#{}", name, n), ms);
  }
  return out;
}

void encode_video(const fs::path& frames_dir, const std::string& pattern, const fs::path& video,
                  double fps) {
  const std::string command = fmt::format(
      "ffmpeg -y -loglevel error -framerate {} -i {} -c:v libx264 -pix_fmt yuv420p "
      "-movflags +faststart {}",
      fps, shell_quote((frames_dir / pattern).string()), shell_quote(video.string()));
  if (std::system(command.c_str()) != 0) {
    throw RuntimeError(fmt::format("ffmpeg failed to encode {}", video.string()));
  }
}

void run_capture(const CaptureOptions& o, const CommonOptions& common) {
  const auto [width, height] = parse_size(common.size);
  if (common.frames <= 0) throw InputError("capture needs --frames N");
  const auto frames = static_cast<std::uint32_t>(common.frames);
  if (o.format != "exr" && o.format != "png") {
    throw InputError(fmt::format("--format {}: expected exr or png", o.format));
  }
  const fs::path out(o.out);
  if (fs::exists(out) && !fs::is_directory(out)) {
    throw InputError(fmt::format("--out {}: exists and is not a directory", o.out));
  }
  if (!o.video.empty()) {
    if (fs::path(o.video).extension() != ".mp4") {
      throw InputError(fmt::format("--video {}: expected a .mp4 file", o.video));
    }
    if (!have_ffmpeg()) {
      throw InputError("--video needs ffmpeg on the PATH (Debian: apt-get install ffmpeg)");
    }
  }
  const auto level = std::make_shared<const Level>(load_level_argument(o.level));
  if (!o.path.empty() && !level->find_path(o.path)) {
    throw InputError(fmt::format("--path {}: {} has no camera path of that name", o.path,
                                 level->source.string()));
  }
  const lighting::IntegratorConfig config = integrator_config(o.integrator, common, *level);
  // What the frames and the video show: --output, else raw EXR frames and a denoised PNG/video.
  using lighting::FrameOutput;
  const FrameOutput frame_output = !o.output.empty() ? lighting::parse_frame_output(o.output)
                                   : o.format == "png" ? FrameOutput::Denoised
                                                       : FrameOutput::Raw;
  const FrameOutput video_output =
      !o.output.empty() ? frame_output : FrameOutput::Denoised;
  const bool denoise = frame_output == FrameOutput::Denoised ||
                       (!o.video.empty() && video_output == FrameOutput::Denoised);
  require_denoised_for_render_scale(o.render_scale, frame_output,
                                    "add --output denoised, or --format png");

  runtime::Device device({.selector = common.device});
  runtime::ShaderLibrary shaders;
  const double fps = 60.0;
  lighting::HeadlessSession session(device, shaders, level,
                                    {.integrator = config,
                                     .width = width,
                                     .height = height,
                                     .seed = common.seed,
                                     .fixed_dt = 1.0 / fps,
                                     .output = denoise ? FrameOutput::Denoised : FrameOutput::Raw,
                                     .render_scale = o.render_scale});
  if (!o.path.empty()) session.world().set_camera_path(o.path);  // InputError when unknown
  session.warm_up();

  const fs::path parent = out.has_parent_path() ? out.parent_path() : fs::path(".");
  fs::create_directories(parent);
  StagingDir staging{parent / fmt::format(".{}.capture-{}", out.filename().string(), ::getpid())};
  fs::create_directories(staging.path);

  std::ofstream csv(staging.path / "timings.csv");
  std::vector<std::string> columns;
  float exposure = o.exposure;
  const bool png_frames = o.format == "png";
  // Encode from separate tonemapped PNGs unless the frames are already the video's PNGs.
  const bool video_pngs = !o.video.empty() && !(png_frames && frame_output == video_output);
  if (video_pngs) fs::create_directories(staging.path / "video_frames");
  Progress progress("capture", frames, common.quiet);
  for (std::uint32_t k = 0; k < frames; ++k) {
    runtime::ImageRGBA32F shown;  // the session's output (denoised when anything needs it)
    runtime::ImageRGBA32F raw;
    const bool need_raw = denoise && (frame_output == FrameOutput::Raw ||
                                      (video_pngs && video_output == FrameOutput::Raw));
    const lighting::FrameTiming t =
        session.render(session.step_world(), &shown, need_raw ? &raw : nullptr);
    const runtime::ImageRGBA32F& image = frame_output == FrameOutput::Raw && need_raw ? raw : shown;
    const runtime::ImageRGBA32F& video_image =
        video_output == FrameOutput::Raw && need_raw ? raw : shown;
    const std::vector<std::pair<std::string, double>> named = pass_columns(t.passes);
    if (k == 0) {
      if (exposure <= 0.0f) exposure = lighting::auto_exposure(video_image);
      csv << "frame,frame_ms,frame_wall_ms";
      for (const auto& [column, ms] : named) {
        columns.push_back(column);
        csv << ',' << column;
      }
      csv << '\n';
    }
    const std::map<std::string, double> by_column(named.begin(), named.end());
    csv << k << ',' << t.gpu_ms << ',' << t.wall_ms;
    for (const std::string& c : columns) {
      const auto it = by_column.find(c);
      csv << ',' << (it != by_column.end() ? it->second : 0.0);
    }
    csv << '\n';
    const std::string name = fmt::format("frame_{:04}.{}", k, o.format);
    runtime::write_image(staging.path / name, image, exposure);
    if (video_pngs) {
      runtime::write_image(staging.path / "video_frames" / fmt::format("frame_{:04}.png", k),
                           video_image, exposure);
    }
    progress.update(k + 1, fmt::format("{:.1f} ms", t.gpu_ms));
  }
  progress.finish();
  csv.close();
  if (!csv) throw RuntimeError("capture: timings.csv write failed");

  const std::string settings_preset = common.preset;
  nlohmann::json settings = nlohmann::json::object();
  for (const auto& [key, value] : config.settings) settings[key] = value;
  const nlohmann::json meta = {
      {"level", level->name},
      {"level_file", level->source.string()},
      {"camera_path", o.path.empty() ? level->camera_path : o.path},
      {"integrator", config.name},
      {"preset", settings_preset},
      {"settings", settings},
      {"size", {width, height}},
      {"render_scale", o.render_scale},
      {"internal_size", {session.renderer().width(), session.renderer().height()}},
      {"frames", frames},
      {"fixed_dt", 1.0 / fps},
      {"seed", common.seed},
      {"format", o.format},
      {"output", lighting::frame_output_name(frame_output)},
      {"video_output", o.video.empty() ? nlohmann::json(nullptr)
                                       : nlohmann::json(lighting::frame_output_name(video_output))},
      {"denoise", [&] {
         nlohmann::json d = nlohmann::json::object();
         for (const auto& [key, value] : lighting::describe_denoise_settings(
                  lighting::make_denoise_settings(config.preset, config.denoise))) {
           d[key] = value;
         }
         return d;
       }()},
      {"exposure", exposure},
      {"device", {{"name", device.info().name},
                  {"driver", device.info().driver},
                  {"vulkan", device.info().api_version}}},
      {"versions", {{"lantern", LANTERN_VERSION}}},
  };
  std::ofstream(staging.path / "capture.json") << meta.dump(2) << '\n';

  if (!o.video.empty()) {
    encode_video(video_pngs ? staging.path / "video_frames" : staging.path,
                 "frame_%04d.png", staging.path / "video.mp4", fps);
  }
  // Everything succeeded: move the files into place.
  fs::create_directories(out);
  fs::remove_all(staging.path / "video_frames");
  for (const auto& entry : fs::directory_iterator(staging.path)) {
    if (entry.path().filename() == "video.mp4") continue;
    fs::rename(entry.path(), out / entry.path().filename());
  }
  if (!o.video.empty()) {
    const fs::path video(o.video);
    if (video.has_parent_path()) fs::create_directories(video.parent_path());
    fs::rename(staging.path / "video.mp4", video);
  }
  log::info("captured {} frames of {} into {}", frames, level->name, o.out);
  if (device.validation_enabled() && device.validation_errors() > 0) {
    throw RuntimeError(fmt::format("{} Vulkan validation error(s)", device.validation_errors()));
  }
}

}  // namespace

void add_capture_command(CLI::App& root, CommonOptions& options) {
  auto opts = std::make_shared<CaptureOptions>();
  auto* cmd = root.add_subcommand("capture", "Scripted flythrough: frames, timings.csv, capture.json");
  add_common_flags(*cmd, options);
  cmd->add_option("LEVEL", opts->level,
                  "Level: a .json/.gltf/.glb file or a name under content/levels/")
      ->required();
  add_integrator_option(*cmd, opts->integrator)->capture_default_str();
  cmd->add_option("--path", opts->path, "Camera path to follow (default: the level's)");
  cmd->add_option("--out", opts->out, "Output directory")->required();
  cmd->add_option("--format", opts->format, "exr (linear) or png (tonemapped)")
      ->capture_default_str();
  cmd->add_option("--video", opts->video, "Also encode an .mp4 with ffmpeg");
  cmd->add_option("--output", opts->output,
                  "raw or denoised frames and video; default raw EXR frames, denoised PNG "
                  "frames and video")
      ->check(CLI::IsMember({"raw", "denoised"}));
  add_render_scale_option(*cmd, opts->render_scale,
                          "Internal size of the denoised frames and video as a fraction of "
                          "--size (upscale.temporal reconstructs them at --size, as play's "
                          "dynamic resolution does); needs denoised frames (--output denoised or "
                          "--format png)");
  cmd->add_option("--exposure", opts->exposure,
                  "PNG/video exposure (default: automatic from the first frame, then fixed)")
      ->check(CLI::Range(1e-6f, 1e6f));
  cmd->callback([opts, &options] { run_capture(*opts, options); });
}

}  // namespace lantern::app
