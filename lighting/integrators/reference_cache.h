// Converged reference images, cached on disk. A reference is integrators.reference at frame K of a
// level (the world stepped K frames, then that snapshot held still), `frames` frames of `spp`
// samples per pixel each averaged (total spp x frames samples per pixel, each frame with its own
// random numbers). Cached as a linear EXR named by a key over everything that changes the image:
// the level's path and content hash (meshes, materials, instances, lights, camera, paths,
// environment map file bytes, settings, the source file's bytes), frame, size, spp, frames, seed
// and the reference settings, plus a format version bumped when the integrator's output changes.
// Directory: $LANTERN_CACHE_DIR, else <build dir>/reference-cache. Writes are atomic
// (runtime/image write_image: temporary file + rename), so concurrent test processes never read a
// half-written file; the standard error is written first and an entry without it is rendered
// again. Used by tests, and later by `lantern trade` and the bias tests.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/scene/level.h"
#include "runtime/image/image.h"
#include "runtime/runtime_fwd.h"

namespace lantern::lighting {

struct ReferenceRequest {
  std::uint32_t width = 320;
  std::uint32_t height = 180;
  std::uint32_t frame = 0;    // level frame K (world steps before the snapshot)
  std::uint32_t spp = 64;     // samples per pixel per frame
  std::uint32_t frames = 16;  // frames averaged
  std::uint32_t seed = 1;     // the reference's samples
  // The world's seed (flickering lights follow it) when it differs from `seed`: the run the
  // reference is measured against, so that both show the same world while their samples differ.
  std::optional<std::uint32_t> world_seed;
  std::vector<std::pair<std::string, std::string>> settings;  // reference settings (--set)
};

// The cache file name for `request` on `level` (no directory): "<level name>-<key hex>.exr".
std::string reference_cache_name(const Level& level, const ReferenceRequest& request);
// $LANTERN_CACHE_DIR, else <build dir>/reference-cache.
std::filesystem::path reference_cache_dir();

struct ReferenceImage {
  runtime::ImageRGBA32F image;
  // The image's standard error per pixel and channel, from the spread of its frames (empty for a
  // reference of one frame): runtime::relative_mse_of_noise(image, standard_error) is a lower
  // bound on the reference's own noise, which every relMSE measured against it carries.
  runtime::ImageRGBA32F standard_error;
  std::filesystem::path path;  // the cache file (its standard error beside it: .stderr.exr)
  bool cache_hit = false;
};

// The reference for `request`: read from the cache when present (and of the requested size),
// else rendered (render_offline with the reference integrator, averaged, animate off) and written.
ReferenceImage reference_image(runtime::Device& device, runtime::ShaderLibrary& shaders,
                               std::shared_ptr<const Level> level, const ReferenceRequest& request);

}  // namespace lantern::lighting
