// `lantern trade LEVEL [--presets a,b,...] [--variant NAME:K=V;K=V] [--frames N] --out DIR`
// (CLI.md): the speed/accuracy trade, measured. Each ReSTIR preset (and --variant), and the
// baseline, runs the level's path for N frames; frame ms is the median GPU frame time and the
// error is the relMSE against cached converged references at a few frames spread over the run
// (lighting/integrators/reference_cache.h). Also measured: the baseline at equal time (as many
// baseline frames of the same instant averaged as fit in one ReSTIR frame). Writes trade.json,
// trade.csv and trade.png (error against ms, log-log, Pareto front marked). With --render-scale
// below 1 the denoised frames are rendered at that internal size and upscaled (upscale.temporal)
// to --size, as `play`'s dynamic resolution shows them; the raw columns stay at --size, the
// unbiased image the denoised one is measured against. Flicker: the change between consecutive
// frames over the run's last --flicker-pairs pairs, plain and moved along the scene's motion
// (lighting/frame/motion_flicker.h), each over the references' own.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <numeric>
#include <set>
#include <string>
#include <vector>

#include "apps/lantern/commands.h"
#include "apps/lantern/progress.h"
#include "engine/core/error.h"
#include "engine/core/log.h"
#include "engine/level/level_loader.h"
#include "engine/perf/pareto.h"
#include "engine/perf/statistics.h"
#include "lighting/frame/headless_session.h"
#include "lighting/frame/motion_flicker.h"
#include "lighting/integrators/offline_render.h"
#include "lighting/integrators/reference_cache.h"
#include "runtime/core/device.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/image/image_io.h"
#include "runtime/image/image_metrics.h"
#include "runtime/image/log_log_plot.h"

namespace lantern::app {
namespace {

namespace fs = std::filesystem;

struct TradeOptions {
  std::string level;
  std::string presets = "fast,balanced,quality";
  std::vector<std::string> variants;  // NAME:KEY=VALUE;KEY=VALUE
  std::string out;
  std::uint32_t eval_frames = 4;
  std::uint32_t reference_spp = 64;
  std::uint32_t reference_frames = 16;
  bool no_baseline = false;
  bool images = false;  // write the last evaluated frame's images beside trade.json
  float render_scale = 1.0f;  // the denoised frames' internal size / --size
  // Consecutive frame pairs the flicker is averaged over, the run's last; the default is cut to
  // the frames there are, an explicit --flicker-pairs is not.
  std::uint32_t flicker_pairs = 3;
  bool flicker_pairs_given = false;
};

// The consecutive frame pairs (f, f+1), f = first .. last() - 1, the flicker is measured over.
struct FlickerPairs {
  std::uint32_t first = 0;
  // 0: a run of one frame, no flicker.
  std::uint32_t count = 0;
  // The last pair's second frame.
  std::uint32_t last() const { return first + count; }
  bool holds(std::uint32_t k) const { return count > 0 && k >= first && k <= last(); }
  bool ends_pair(std::uint32_t k) const { return k > first && k <= last(); }
};

struct Config {
  std::string name;
  lighting::IntegratorConfig integrator;
  bool baseline = false;  // the baseline row (the others are ReSTIR presets and variants)
};

double mean_of(const std::vector<double>& v) {
  double s = 0.0;
  for (double e : v) s += e;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

struct Row {
  Config config;
  double frame_ms = 0.0;       // GPU ms of the raw frame (the denoise.* passes not included)
  double frame_wall_ms = 0.0;
  double denoise_ms = 0.0;     // GPU ms of the denoise.* and upscale.* passes
  double denoised_frame_ms = 0.0;  // GPU ms of the denoised frame, at --render-scale
  std::vector<double> relmse;  // per evaluated frame, raw image
  std::vector<double> relmse_denoised;
  std::vector<double> mean_ratio_denoised;  // mean(denoised) / mean(reference) per frame
  std::vector<double> mean_ratio_raw;       // mean(raw) / mean(reference) per frame
  // Per flicker pair (f, f+1): the mean squared change from frame f to f+1 relative to the mean
  // square of frame f+1's reference; the columns are their means.
  std::vector<double> flicker_raw;
  std::vector<double> flicker_denoised;
  // The same with frame f moved along the scene's motion (motion_flicker.h).
  std::vector<double> flicker_mc_raw;
  std::vector<double> flicker_mc_denoised;
  // --images: the last evaluated frame.
  runtime::ImageRGBA32F last_raw, last_denoised;
  double mean_relmse() const { return mean_of(relmse); }
};

// Mean over pixels and RGB of (a - b)^2 over the mean of reference^2: the frame-to-frame change
// of a sequence, comparable between the images a preset makes and the reference's own.
double frame_change(const runtime::ImageRGBA32F& a, const runtime::ImageRGBA32F& b,
                    const runtime::ImageRGBA32F& reference) {
  double change = 0.0;
  double power = 0.0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    if (i % 4 == 3) continue;
    const double d = static_cast<double>(a.pixels[i]) - b.pixels[i];
    change += d * d;
    power += static_cast<double>(reference.pixels[i]) * reference.pixels[i];
  }
  return power > 0.0 ? change / power : 0.0;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= s.size()) {
    const std::size_t end = std::min(s.find(sep, start), s.size());
    if (end > start) out.push_back(s.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

// Frames K at which the error is measured: `count` spread over [0, frames), always the last.
std::vector<std::uint32_t> eval_frames(std::uint32_t frames, std::uint32_t count) {
  std::set<std::uint32_t> ks;
  count = std::max(1u, std::min(count, frames));
  for (std::uint32_t i = 1; i <= count; ++i) ks.insert(frames * i / count - 1);
  return {ks.begin(), ks.end()};
}

std::vector<Config> configs(const TradeOptions& o, const CommonOptions& common,
                            const Level& level) {
  std::vector<Config> out;
  for (const std::string& preset : split(o.presets, ',')) {
    if (preset != "fast" && preset != "balanced" && preset != "quality") {
      throw InputError(fmt::format("--presets: unknown preset '{}' (fast, balanced, quality)",
                                   preset));
    }
    CommonOptions c = common;
    c.preset = preset;
    out.push_back({preset, integrator_config("restir", c, level)});
  }
  for (const std::string& v : o.variants) {
    const std::size_t colon = v.find(':');
    if (colon == std::string::npos || colon == 0) {
      throw InputError(fmt::format("--variant {}: expected NAME:KEY=VALUE;KEY=VALUE", v));
    }
    const std::string name = v.substr(0, colon);
    if (name.find_first_of("/\\") != std::string::npos || name == "." || name == "..") {
      throw InputError(fmt::format("--variant {}: the name '{}' must not be a path (it names "
                                   "the row and --images' files)", v, name));
    }
    CommonOptions c = common;
    for (const std::string& kv : split(v.substr(colon + 1), ';')) c.settings.push_back(kv);
    out.push_back({name, integrator_config("restir", c, level)});
  }
  if (!o.no_baseline)
    out.push_back({"baseline", integrator_config("baseline", common, level), true});
  // Row names label the tables and --images' files: one row each.
  for (std::size_t i = 0; i < out.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (out[i].name == out[j].name) {
        throw InputError(fmt::format("trade: two rows are named '{}' (a preset, a variant or the "
                                     "baseline): name each variant apart",
                                     out[i].name));
      }
    }
  }
  if (out.empty()) throw InputError("trade: nothing to compare (no presets, variants or baseline)");
  return out;
}

nlohmann::json settings_json(const lighting::IntegratorConfig& c) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [k, v] : c.settings) j[k] = v;
  return j;
}

void run_trade(const TradeOptions& o, const CommonOptions& common) {
  const auto [width, height] = parse_size(common.size);
  const std::uint32_t frames = common.frames > 0 ? static_cast<std::uint32_t>(common.frames) : 16u;
  if (o.eval_frames == 0 || o.reference_spp == 0 || o.reference_frames == 0) {
    throw InputError("--eval-frames, --reference-spp and --reference-frames must be positive");
  }
  const fs::path out(o.out);
  if (fs::exists(out) && !fs::is_directory(out)) {
    throw InputError(fmt::format("--out {}: exists and is not a directory", o.out));
  }
  const auto level = std::make_shared<const Level>(load_level_argument(o.level));
  const std::vector<Config> cfgs = configs(o, common, *level);
  const std::vector<std::uint32_t> ks = eval_frames(frames, o.eval_frames);

  // Flicker: the change from frame f to f+1 over the run's last pairs, of each preset's raw and
  // denoised images and of the references (each frame of a pair gets its reference).
  if (o.flicker_pairs_given && o.flicker_pairs > frames - 1) {
    throw InputError(
        fmt::format("--flicker-pairs {}: {} frames hold {} consecutive pair(s); raise "
                    "--frames or lower --flicker-pairs",
                    o.flicker_pairs, frames, frames - 1));
  }
  const FlickerPairs pairs{.first = frames - 1 - std::min(o.flicker_pairs, frames - 1),
                           .count = std::min(o.flicker_pairs, frames - 1)};
  std::vector<std::uint32_t> extra_reference_frames;  // a pair's frames that are not evaluated
  for (std::uint32_t k = pairs.first; k <= pairs.last(); ++k) {
    if (pairs.holds(k) && !std::binary_search(ks.begin(), ks.end(), k)) {
      extra_reference_frames.push_back(k);
    }
  }
  runtime::Device device({.selector = common.device});
  runtime::ShaderLibrary shaders;
  Progress progress("trade", ks.size() + extra_reference_frames.size() + 2 * cfgs.size() * frames,
                    common.quiet);
  std::uint64_t done = 0;

  // References first (cached on disk: later runs skip the expensive part).
  std::vector<runtime::ImageRGBA32F> references;
  // Each evaluated reference's own noise (relative_mse_of_noise; negative when unknown: a
  // reference of one frame).
  std::vector<double> reference_noise;
  std::map<std::uint32_t, runtime::ImageRGBA32F> pair_references;  // extra_reference_frames'
  lighting::ReferenceRequest ref_request{.width = width,
                                         .height = height,
                                         .frame = 0,
                                         .spp = o.reference_spp,
                                         .frames = o.reference_frames,
                                         .seed = common.seed + 1000u,
                                         .world_seed = common.seed,
                                         .settings = {}};
  for (std::uint32_t k : ks) {
    ref_request.frame = k;
    lighting::ReferenceImage ref = lighting::reference_image(device, shaders, level, ref_request);
    progress.update(++done, fmt::format("reference frame {}{}", k, ref.cache_hit ? " (cached)" : ""));
    reference_noise.push_back(ref.standard_error.pixels.empty()
                                  ? -1.0
                                  : runtime::relative_mse_of_noise(ref.image, ref.standard_error));
    references.push_back(std::move(ref.image));
  }
  for (std::uint32_t k : extra_reference_frames) {
    ref_request.frame = k;
    lighting::ReferenceImage ref = lighting::reference_image(device, shaders, level, ref_request);
    progress.update(++done,
                    fmt::format("reference frame {}{}", k, ref.cache_hit ? " (cached)" : ""));
    pair_references[k] = std::move(ref.image);
  }
  auto reference_at = [&](std::uint32_t k) -> const runtime::ImageRGBA32F& {
    const auto it = std::lower_bound(ks.begin(), ks.end(), k);
    if (it != ks.end() && *it == k) return references[static_cast<std::size_t>(it - ks.begin())];
    return pair_references.at(k);
  };
  std::vector<double> flicker_ref;  // per pair
  for (std::uint32_t f = pairs.first; f < pairs.last(); ++f) {
    flicker_ref.push_back(frame_change(reference_at(f + 1), reference_at(f), reference_at(f + 1)));
  }
  // The references' noise, over the evaluated frames as the rows' relMSE is (unknown if any is).
  const bool noise_known = std::none_of(reference_noise.begin(), reference_noise.end(),
                                        [](double n) { return n < 0.0; });
  const double noise_ref = noise_known ? mean_of(reference_noise) : -1.0;

  // The motion-compensated flicker compares each pixel of frame f+1 with where its point was in
  // frame f: the first raw run's G-buffers of the two frames say where, and which pixels show
  // the same surface in both (the raw run has no jitter; every run renders the same camera and
  // objects, so one warp per pair serves the references and every row).
  std::vector<lighting::MotionWarp> warps;  // per pair
  lighting::GBufferTexels previous_gbuffer;
  std::vector<double> flicker_mc_ref;  // per pair

  std::vector<Row> rows;
  std::pair<std::uint32_t, std::uint32_t> denoised_internal{width, height};
  for (const Config& cfg : cfgs) {
    Row row{cfg};
    // The same frames twice: the raw output (what `render` writes: the raw columns and the frame
    // time) and the denoised output (its columns and the denoiser's time). An integrator may
    // render the denoiser's input differently (RestirSettings::temporal_permutation), so the
    // raw columns are not read from the denoiser's input.
    for (const lighting::FrameOutput output :
         {lighting::FrameOutput::Raw, lighting::FrameOutput::Denoised}) {
      const bool denoised = output == lighting::FrameOutput::Denoised;
      lighting::HeadlessSession session(device, shaders, level,
                                        {.integrator = cfg.integrator,
                                         .width = width,
                                         .height = height,
                                         .seed = common.seed,
                                         .output = output,
                                         .render_scale = denoised ? o.render_scale : 1.0f});
      session.warm_up();
      if (denoised) denoised_internal = {session.renderer().width(), session.renderer().height()};
      std::vector<double> gpu, wall, denoise, denoised_gpu;
      std::size_t next = 0;
      runtime::ImageRGBA32F previous;
      for (std::uint32_t k = 0; k < frames; ++k) {
        const bool evaluate = next < ks.size() && ks[next] == k;
        const bool keep = evaluate || pairs.holds(k);
        runtime::ImageRGBA32F image;
        const bool read_gbuffer = pairs.holds(k) && rows.empty() && !denoised;
        lighting::GBufferTexels gbuffer;
        const lighting::FrameTiming t =
            session.render(session.step_world(), keep ? &image : nullptr, nullptr,
                           read_gbuffer ? &gbuffer : nullptr);
        if (read_gbuffer && pairs.ends_pair(k)) {
          warps.push_back(lighting::motion_warp(previous_gbuffer, gbuffer));
          flicker_mc_ref.push_back(lighting::motion_compensated_change(
              reference_at(k), reference_at(k - 1), reference_at(k), warps.back()));
        }
        if (read_gbuffer) previous_gbuffer = std::move(gbuffer);
        if (denoised) {
          double denoise_ms = 0.0;
          for (const auto& [name, ms] : t.passes) {
            if (name.rfind("denoise.", 0) == 0 || name.rfind("upscale.", 0) == 0) denoise_ms += ms;
          }
          denoise.push_back(denoise_ms);
          denoised_gpu.push_back(t.gpu_ms);
        } else {
          gpu.push_back(t.gpu_ms);
          wall.push_back(t.wall_ms);
        }
        if (pairs.ends_pair(k)) {
          const runtime::ImageRGBA32F& ref = reference_at(k);
          (denoised ? row.flicker_denoised : row.flicker_raw)
              .push_back(frame_change(image, previous, ref));
          (denoised ? row.flicker_mc_denoised : row.flicker_mc_raw)
              .push_back(lighting::motion_compensated_change(image, previous, ref,
                                                             warps.at(k - 1 - pairs.first)));
        }
        if (evaluate) {
          const runtime::ImageRGBA32F& ref = references[next++];
          (denoised ? row.relmse_denoised : row.relmse)
              .push_back(runtime::relative_mse(image, ref));
          const double ref_mean = runtime::mean_rgb(ref);
          (denoised ? row.mean_ratio_denoised : row.mean_ratio_raw)
              .push_back(ref_mean > 0.0 ? runtime::mean_rgb(image) / ref_mean : 0.0);
          if (o.images && next == ks.size()) (denoised ? row.last_denoised : row.last_raw) = image;
        }
        if (keep) previous = std::move(image);
        progress.update(++done, fmt::format("{} frame {} ({})", cfg.name, k,
                                            lighting::frame_output_name(output)));
      }
      if (denoised) {
        row.denoise_ms = perf::summarize(denoise).median;
        row.denoised_frame_ms = perf::summarize(denoised_gpu).median;
      } else {
        row.frame_ms = perf::summarize(gpu).median;
        row.frame_wall_ms = perf::summarize(wall).median;
      }
    }
    rows.push_back(std::move(row));
  }
  progress.finish();

  // Baseline at equal time: for each ReSTIR row, ceil-free round(restir ms / baseline ms) baseline
  // frames of the same instant averaged (what the baseline buys with the same GPU time).
  const auto baseline = std::find_if(rows.begin(), rows.end(), [](const Row& r) {
    return r.config.baseline;
  });
  nlohmann::json equal_time = nlohmann::json::array();
  if (baseline != rows.end() && baseline->frame_ms > 0.0) {
    for (const Row& r : rows) {
      if (r.config.baseline) continue;
      const auto spp = static_cast<std::uint32_t>(
          std::clamp(std::lround(r.frame_ms / baseline->frame_ms), 1l, 256l));
      double sum = 0.0;
      for (std::size_t i = 0; i < ks.size(); ++i) {
        lighting::OfflineRenderRequest req;
        req.integrator = baseline->config.integrator;
        req.width = width;
        req.height = height;
        req.frames = spp;
        req.first_frame = ks[i];
        req.average = true;
        req.seed = common.seed;
        req.animate = false;
        sum += runtime::relative_mse(
            lighting::render_offline(device, shaders, level, req).images.at(0), references[i]);
      }
      const double base_err = sum / static_cast<double>(ks.size());
      equal_time.push_back({{"restir", r.config.name},
                            {"restir_frame_ms", r.frame_ms},
                            {"restir_relmse", r.mean_relmse()},
                            {"baseline_frames_averaged", spp},
                            {"baseline_relmse", base_err},
                            {"relmse_ratio", r.mean_relmse() > 0.0 ? base_err / r.mean_relmse() : 0.0}});
    }
  }

  // Pareto front over (frame ms, relMSE).
  std::vector<std::pair<double, double>> points;
  for (const Row& r : rows) points.emplace_back(r.frame_ms, r.mean_relmse());
  const std::vector<std::size_t> front = perf::pareto_front(points);
  auto on_front = [&](std::size_t i) {
    return std::find(front.begin(), front.end(), i) != front.end();
  };

  // Flicker columns: the means over the pairs, and the rows' denoised means over the references'.
  const double flicker_ref_mean = mean_of(flicker_ref);
  const double flicker_mc_ref_mean = mean_of(flicker_mc_ref);
  auto flicker_ratio = [](const std::vector<double>& row, double reference) {
    return reference > 0.0 ? mean_of(row) / reference : 0.0;
  };
  std::vector<std::uint32_t> pair_first_frames;
  for (std::uint32_t f = pairs.first; f < pairs.last(); ++f) pair_first_frames.push_back(f);
  std::vector<std::size_t> compared_pixels;
  for (const lighting::MotionWarp& w : warps) compared_pixels.push_back(w.valid_count);
  const std::size_t compared_pixels_mean =
      compared_pixels.empty()
          ? 0
          : std::accumulate(compared_pixels.begin(), compared_pixels.end(), std::size_t{0}) /
                compared_pixels.size();

  fs::create_directories(out);
  nlohmann::json jrows = nlohmann::json::array();
  std::string csv =
      "name,integrator,frame_ms,frame_wall_ms,relmse,pareto,denoise_ms,relmse_denoised,"
      "mean_ratio_denoised,flicker_raw,flicker_denoised,settings,denoised_frame_ms,"
      "flicker_mc_raw,flicker_mc_denoised\n";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    const std::string& integrator = r.config.integrator.name;
    jrows.push_back(
        {{"name", r.config.name},
         {"integrator", integrator},
         {"preset", r.config.integrator.preset},
         {"frame_ms", r.frame_ms},
         {"frame_wall_ms", r.frame_wall_ms},
         {"relmse", r.mean_relmse()},
         {"relmse_per_frame", r.relmse},
         {"denoise_ms", r.denoise_ms},
         {"denoised_frame_ms", r.denoised_frame_ms},
         {"relmse_denoised", mean_of(r.relmse_denoised)},
         {"relmse_denoised_per_frame", r.relmse_denoised},
         {"relmse_reduction",
          mean_of(r.relmse_denoised) > 0.0 ? r.mean_relmse() / mean_of(r.relmse_denoised) : 0.0},
         {"mean_ratio_denoised", mean_of(r.mean_ratio_denoised)},
         {"mean_ratio_raw", mean_of(r.mean_ratio_raw)},
         {"flicker_raw", mean_of(r.flicker_raw)},
         {"flicker_denoised", mean_of(r.flicker_denoised)},
         {"flicker_ratio", flicker_ratio(r.flicker_denoised, flicker_ref_mean)},
         {"flicker_mc_raw", mean_of(r.flicker_mc_raw)},
         {"flicker_mc_denoised", mean_of(r.flicker_mc_denoised)},
         {"flicker_mc_ratio", flicker_ratio(r.flicker_mc_denoised, flicker_mc_ref_mean)},
         {"flicker_per_pair",
          {{"raw", r.flicker_raw},
           {"denoised", r.flicker_denoised},
           {"mc_raw", r.flicker_mc_raw},
           {"mc_denoised", r.flicker_mc_denoised}}},
         {"pareto", on_front(i)},
         {"settings", settings_json(r.config.integrator)}});
    std::string settings;
    for (const auto& [k, v] : r.config.integrator.settings) settings += fmt::format("{}={};", k, v);
    csv += fmt::format(
        "{},{},{:.4f},{:.4f},{:.6g},{},{:.4f},{:.6g},{:.5f},{:.6g},{:.6g},{},{:.4f},{:.6g},"
        "{:.6g}\n",
        r.config.name, integrator, r.frame_ms, r.frame_wall_ms, r.mean_relmse(),
        on_front(i) ? 1 : 0, r.denoise_ms, mean_of(r.relmse_denoised),
        mean_of(r.mean_ratio_denoised), mean_of(r.flicker_raw), mean_of(r.flicker_denoised),
        settings, r.denoised_frame_ms, mean_of(r.flicker_mc_raw), mean_of(r.flicker_mc_denoised));
  }
  const nlohmann::json j = {
      {"level", level->name},
      {"size", {width, height}},
      // The denoised frames' internal size / size (upscale.temporal below 1); raw is at size.
      {"render_scale", o.render_scale},
      {"denoised_internal_size", {denoised_internal.first, denoised_internal.second}},
      {"frames", frames},
      {"seed", common.seed},
      {"device", device.info().name},
      {"evaluated_frames", ks},
      // Frame-to-frame change from frame f to f+1 relative to frame f+1's reference's mean
      // square, averaged over the pairs (first frames f: pair_first_frames; frames: the first
      // and the last frame they span); the rows' flicker_ratio is their denoised flicker over
      // this. motion_compensated: the same with frame f moved along the scene's motion, over the
      // pixels both frames show as the same surface (compared_pixels: their mean over the
      // pairs); the rows' flicker_mc_ratio is their denoised one over this reference's.
      {"flicker",
       {{"frames",
         pairs.count > 0 ? nlohmann::json::array({pairs.first, pairs.last()}) : nlohmann::json()},
        {"pairs", pairs.count},
        {"pair_first_frames", pair_first_frames},
        {"reference", flicker_ref_mean},
        {"reference_per_pair", flicker_ref},
        {"motion_compensated",
         {{"reference", flicker_mc_ref_mean},
          {"reference_per_pair", flicker_mc_ref},
          {"compared_pixels", compared_pixels_mean},
          {"compared_pixels_per_pair", compared_pixels}}}}},
      {"reference",
       {{"integrator", "reference"},
        {"spp_per_frame", o.reference_spp},
        {"frames_averaged", o.reference_frames},
        {"seed", ref_request.seed},
        // The references' own relMSE against the converged image, from the spread
        // of their frames (a lower bound: a heavy tail's rare samples may never have
        // come up): no row is resolved below it (null: unknown).
        {"noise_relmse", noise_known ? nlohmann::json(noise_ref) : nlohmann::json()}}},
      {"rows", jrows},
      {"equal_time", equal_time},
  };
  std::ofstream(out / "trade.json") << j.dump(2) << '\n';
  std::ofstream(out / "trade.csv") << csv;
  if (o.images) {
    runtime::write_exr(out / "reference.exr", references.back());
    for (const Row& r : rows) {
      runtime::write_exr(out / fmt::format("{}_raw.exr", r.config.name), r.last_raw);
      runtime::write_exr(out / fmt::format("{}_denoised.exr", r.config.name), r.last_denoised);
    }
  }

  runtime::LogLogPlot plot;
  plot.title = fmt::format("{} {}x{}: error vs frame time ({} frames)", level->name, width,
                           height, frames);
  plot.x_label = "GPU frame time (ms)";
  plot.y_label = "relMSE vs reference";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    plot.points.push_back({rows[i].frame_ms, rows[i].mean_relmse(), rows[i].config.name,
                           on_front(i)});
  }
  for (std::size_t i : front) plot.line.emplace_back(rows[i].frame_ms, rows[i].mean_relmse());
  runtime::write_log_log_plot(out / "trade.png", plot);

  if (denoised_internal != std::pair{width, height}) {
    std::printf("denoised frames rendered at %ux%u and upscaled to %ux%u (--render-scale %g)\n",
                denoised_internal.first, denoised_internal.second, width, height,
                static_cast<double>(o.render_scale));
  }
  std::printf("%-14s %-9s %10s %12s %6s %10s %10s %12s %8s %8s %10s %10s %10s %10s\n", "config",
              "integr.", "frame ms", "relMSE", "pareto", "den. frame", "denoise ms", "denoised",
              "mean", "raw mean", "flicker", "x ref", "mc flicker", "x ref");
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    std::printf(
        "%-14s %-9s %10.2f %12.4g %6s %10.2f %10.2f %12.4g %8.4f %8.4f %10.4g %10.3g %10.4g "
        "%10.3g\n",
        r.config.name.c_str(), r.config.integrator.name.c_str(), r.frame_ms, r.mean_relmse(),
        on_front(i) ? "*" : "", r.denoised_frame_ms, r.denoise_ms, mean_of(r.relmse_denoised),
        mean_of(r.mean_ratio_denoised), mean_of(r.mean_ratio_raw), mean_of(r.flicker_denoised),
        flicker_ratio(r.flicker_denoised, flicker_ref_mean), mean_of(r.flicker_mc_denoised),
        flicker_ratio(r.flicker_mc_denoised, flicker_mc_ref_mean));
  }
  if (pairs.count > 0) {
    std::printf(
        "reference flicker %.4g (mean of %u frame pair(s), frames %u-%u); motion-compensated "
        "%.4g over %zu of %u pixels on average (the same surface in both frames, no emitter)\n",
        flicker_ref_mean, pairs.count, pairs.first, pairs.last(), flicker_mc_ref_mean,
        compared_pixels_mean, width * height);
  }
  if (noise_known) {
    std::printf("reference noise >= %.4g (its own relMSE from the spread of its %u frames of %u "
                "spp, more where rare bright samples never came up: errors near it are not "
                "resolved; raise --reference-spp)\n",
                noise_ref, o.reference_frames, o.reference_spp);
  }
  for (const auto& e : equal_time) {
    std::printf("equal time vs %s: baseline x%d frames relMSE %.4g = %.1fx ReSTIR's\n",
                e["restir"].get<std::string>().c_str(), e["baseline_frames_averaged"].get<int>(),
                e["baseline_relmse"].get<double>(), e["relmse_ratio"].get<double>());
  }
  if (device.validation_enabled() && device.validation_errors() > 0) {
    throw RuntimeError(fmt::format("{} Vulkan validation error(s)", device.validation_errors()));
  }
}

}  // namespace

void add_trade_command(CLI::App& root, CommonOptions& options) {
  auto opts = std::make_shared<TradeOptions>();
  auto* cmd = root.add_subcommand("trade", "Speed/accuracy sweep: trade.json, trade.csv, trade.png");
  add_common_flags(*cmd, options);
  cmd->add_option("LEVEL", opts->level,
                  "Level: a .json/.gltf/.glb file or a name under content/levels/")
      ->required();
  cmd->add_option("--presets", opts->presets, "ReSTIR presets to run, comma-separated")
      ->capture_default_str();
  cmd->add_option("--variant", opts->variants,
                  "Extra ReSTIR configuration NAME:KEY=VALUE;KEY=VALUE (repeatable)");
  cmd->add_flag("--no-baseline", opts->no_baseline, "Leave the baseline out");
  cmd->add_option("--eval-frames", opts->eval_frames, "Frames at which the error is measured")
      ->capture_default_str();
  cmd->add_option("--reference-spp", opts->reference_spp, "Reference samples per pixel per frame")
      ->capture_default_str();
  cmd->add_option("--reference-frames", opts->reference_frames,
                  "Reference frames averaged (total spp = spp x frames)")
      ->capture_default_str();
  add_render_scale_option(*cmd, opts->render_scale,
                          "Internal size of the denoised frames as a fraction of --size "
                          "(upscale.temporal reconstructs them at --size); the raw frames stay at "
                          "--size");
  cmd->add_option("--flicker-pairs", opts->flicker_pairs,
                  "Consecutive frame pairs at the run's end the flicker is averaged over (each "
                  "frame of a pair gets a reference; at most --frames - 1)")
      ->capture_default_str()
      ->each([opts](const std::string&) { opts->flicker_pairs_given = true; });
  cmd->add_flag("--images", opts->images,
                "Also write the last evaluated frame: reference.exr, NAME_raw.exr, "
                "NAME_denoised.exr");
  cmd->add_option("--out", opts->out, "Output directory")->required();
  cmd->callback([opts, &options] { run_trade(*opts, options); });
}

}  // namespace lantern::app
