// Reference cache: content hash, key, lookup, render-and-store (reference_cache.h).
#include "lighting/integrators/reference_cache.h"

#include <fmt/format.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <system_error>

#include "engine/core/error.h"
#include "engine/core/log.h"
#include "lighting/integrators/integrator_registry.h"
#include "lighting/integrators/offline_render.h"
#include "lighting/integrators/reference_integrator.h"
#include "runtime/image/image_io.h"

namespace lantern::lighting {
namespace {

// Bump when the reference integrator's output changes for the same inputs (estimator, conventions).
// 2: media attenuate (issue 14); 3: media scatter light into camera rays; 4: analytic lights by a
// per-pixel walk (integrators/reference.h kReferenceAnalyticWalkMax); 5: the walk only while it
// costs at most kReferenceAnalyticWalkPerSample lights per sample.
constexpr std::uint32_t kReferenceFormatVersion = 5;

class Fnv1a {
 public:
  void bytes(const void* data, std::size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) {
      hash_ ^= p[i];
      hash_ *= 0x100000001b3ull;
    }
  }
  template <class T>
  void pod(const T& value) {
    bytes(&value, sizeof(T));
  }
  template <class T>
  void array(const std::vector<T>& values) {
    pod(values.size());
    if (!values.empty()) bytes(values.data(), values.size() * sizeof(T));
  }
  void text(const std::string& s) {
    pod(s.size());
    bytes(s.data(), s.size());
  }
  // The file's bytes (or a marker when it cannot be read).
  void file(const std::filesystem::path& path) {
    text(path.string());
    std::ifstream in(path, std::ios::binary);
    if (!in) {
      text("<unreadable>");
      return;
    }
    char buffer[1 << 14];
    std::uint64_t total = 0;
    while (in) {
      in.read(buffer, sizeof(buffer));
      const auto got = static_cast<std::size_t>(in.gcount());
      bytes(buffer, got);
      total += got;
    }
    pod(total);
  }
  std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xcbf29ce484222325ull;
};

void hash_level(Fnv1a& h, const Level& level) {
  h.text(level.name);
  if (!level.source.empty()) h.file(level.source);
  h.pod(level.meshes.size());
  for (const Mesh& m : level.meshes) {
    h.array(m.positions);
    h.array(m.normals);
    h.array(m.uvs);
    h.array(m.uvs1);
    h.array(m.tangents);
    h.array(m.indices);
  }
  h.pod(level.materials.size());
  for (const Material& m : level.materials) {
    h.pod(m.base_color);
    h.pod(m.metallic);
    h.pod(m.roughness);
    h.pod(m.emissive_factor);
    h.pod(m.emissive_strength);
    h.pod(m.specular_factor);
    h.pod(m.specular_color);
    for (const TextureRef* t : {&m.base_color_texture, &m.metallic_roughness_texture,
                                &m.normal_texture, &m.emissive_texture}) {
      h.pod(t->image);
      h.pod(t->texcoord);
    }
  }
  h.pod(level.instances.size());
  for (const Instance& inst : level.instances) {
    h.pod(inst.mesh);
    h.pod(inst.material);
    h.pod(inst.world);
    h.pod(inst.behaviour.has_value());
  }
  h.pod(level.lights.size());
  for (const Light& light : level.lights) {
    h.pod(light.type);
    h.pod(light.color);
    h.pod(light.intensity);
    h.pod(light.range);
    h.pod(light.inner_cone);
    h.pod(light.outer_cone);
    h.pod(light.position);
    h.pod(light.rotation);
    h.pod(light.behaviour.has_value());
  }
  h.pod(level.camera.yfov);
  h.pod(level.camera.aspect);
  h.pod(level.camera.znear);
  h.pod(level.camera.zfar);
  h.pod(level.camera.position);
  h.pod(level.camera.orientation);
  h.text(level.camera_path);
  h.pod(level.paths.size());
  if (level.environment) {
    h.file(level.environment->path);
    h.pod(level.environment->intensity);
    h.pod(level.environment->rotation);
  } else {
    h.text("<no environment>");
  }
  for (const auto& [key, value] : level.settings) {
    h.text(key);
    h.text(value);
  }
  h.pod(level.volumes.size());
  for (const Volume& v : level.volumes) {
    if (!v.file.empty()) h.file(v.file);
    h.pod(v.generator.has_value());
    if (v.generator) {
      h.pod(v.generator->type);
      h.pod(v.generator->seed);
      h.pod(v.generator->size);
      h.pod(v.generator->voxel_size);
    }
    h.text(v.grid);
    h.pod(v.transform.matrix());
    h.pod(v.density_scale);
    h.pod(v.scattering);
    h.pod(v.absorption);
    h.pod(v.anisotropy);
    h.pod(v.behaviour.has_value());
  }
}

std::string sanitized(const std::string& name) {
  std::string out;
  for (char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-';
    out.push_back(ok ? c : '_');
  }
  return out.empty() ? std::string("level") : out.substr(0, 48);
}

}  // namespace

std::string reference_cache_name(const Level& level, const ReferenceRequest& request) {
  Fnv1a h;
  h.pod(kReferenceFormatVersion);
  h.text(level.source.string());
  hash_level(h, level);
  h.pod(request.width);
  h.pod(request.height);
  h.pod(request.frame);
  h.pod(request.spp);
  h.pod(request.frames);
  h.pod(request.seed);
  // Only a world seed of its own makes another key (the entries of requests without one stay).
  if (request.world_seed && *request.world_seed != request.seed) h.pod(*request.world_seed);
  for (const auto& [key, value] : request.settings) {
    h.text(key);
    h.text(value);
  }
  return fmt::format("{}-{}x{}-f{}-{:016x}.exr", sanitized(level.name), request.width,
                     request.height, request.frame, h.value());
}

std::filesystem::path reference_cache_dir() {
  if (const char* dir = std::getenv("LANTERN_CACHE_DIR"); dir != nullptr && dir[0] != '\0') {
    return std::filesystem::path(dir);
  }
  return std::filesystem::path(LANTERN_SHADER_DIR).parent_path() / "reference-cache";
}

ReferenceImage reference_image(runtime::Device& device, runtime::ShaderLibrary& shaders,
                               std::shared_ptr<const Level> level,
                               const ReferenceRequest& request) {
  if (!level) throw InputError("reference_image: no level");
  if (request.width == 0 || request.height == 0 || request.spp == 0 || request.frames == 0) {
    throw InputError(fmt::format("reference: size {}x{}, spp {} and frames {} must be positive",
                                 request.width, request.height, request.spp, request.frames));
  }
  ReferenceImage out;
  out.path = reference_cache_dir() / reference_cache_name(*level, request);
  const std::filesystem::path stderr_path =
      std::filesystem::path(out.path).replace_extension(".stderr.exr");
  const bool with_stderr = request.frames >= 2;
  const auto usable = [&](const runtime::ImageRGBA32F& image) {
    return image.width == request.width && image.height == request.height &&
           image.count_non_finite() == 0;
  };
  std::error_code ec;
  if (std::filesystem::exists(out.path, ec) &&
      (!with_stderr || std::filesystem::exists(stderr_path, ec))) {
    try {
      runtime::ImageRGBA32F cached = runtime::read_image(out.path);
      runtime::ImageRGBA32F cached_stderr;
      if (with_stderr) cached_stderr = runtime::read_image(stderr_path);
      if (usable(cached) && (!with_stderr || usable(cached_stderr))) {
        out.image = std::move(cached);
        out.standard_error = std::move(cached_stderr);
        out.cache_hit = true;
        log::debug("reference: cache hit {}", out.path.string());
        return out;
      }
      log::warn("reference: ignoring cached {} (not {}x{} or not finite)", out.path.string(),
                request.width, request.height);
    } catch (const std::exception& e) {
      log::warn("reference: ignoring unreadable cached {}: {}", out.path.string(), e.what());
    }
  }

  OfflineRenderRequest render;
  render.integrator.name = ReferenceIntegrator::kName;
  render.integrator.spp = request.spp;
  render.integrator.settings = request.settings;
  render.width = request.width;
  render.height = request.height;
  render.frames = request.frames;
  render.first_frame = request.frame;
  render.average = true;
  render.seed = request.seed;
  render.world_seed = request.world_seed;
  render.animate = false;
  OfflineRenderResult result = render_offline(device, shaders, level, render);
  if (result.images.size() != 1) {
    throw RuntimeError(
        fmt::format("reference: expected one averaged image, got {}", result.images.size()));
  }
  out.image = std::move(result.images.front());
  out.standard_error = std::move(result.standard_error);
  std::filesystem::create_directories(out.path.parent_path(), ec);
  if (ec) {
    throw RuntimeError(fmt::format("reference: cannot create cache directory {}: {}",
                                   out.path.parent_path().string(), ec.message()));
  }
  // The standard error first: the mean's file is what marks a complete entry.
  if (with_stderr) runtime::write_image(stderr_path, out.standard_error);
  runtime::write_image(out.path, out.image);
  log::debug("reference: rendered and cached {}", out.path.string());
  return out;
}

}  // namespace lantern::lighting
