// Loader fuzz targets: input bytes -> scratch file -> lantern::load_level.
#include "tests/fuzz/fuzz_targets.h"

#include <unistd.h>

#include <cstring>
#include <fstream>
#include <string>

#include "engine/core/error.h"
#include "engine/core/log.h"
#include "engine/level/level_loader.h"
#include "lighting/textures/texture_set.h"
#include "runtime/image/image_decode.h"

namespace lantern::fuzz {
namespace {

std::filesystem::path& scratch_dir() {
  static std::filesystem::path dir;
  return dir;
}

int load(const std::uint8_t* data, std::size_t size, const char* name) {
  const std::filesystem::path file = scratch_dir() / name;
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    const Level level = load_level(file);
    (void)level;
  } catch (const InputError&) {
    // The expected outcome for bad input.
  }
  return 0;
}

}  // namespace

void init(const std::filesystem::path& assets) {
  namespace fs = std::filesystem;
  scratch_dir() = fs::temp_directory_path() / ("lantern-fuzz-" + std::to_string(::getpid()));
  fs::create_directories(scratch_dir());
  for (const char* name : {"lights_camera.gltf", "animated_mesh.gltf", "sky.hdr", "budget.json"})
    fs::copy_file(assets / name, scratch_dir() / name, fs::copy_options::overwrite_existing);
  // Warnings (degenerate triangles, ignored channels) are expected for fuzzed input; keep stderr
  // for libFuzzer's own output.
  log::set_level(log::Level::Error);
}

void cleanup() {
  std::error_code ignored;
  if (!scratch_dir().empty()) std::filesystem::remove_all(scratch_dir(), ignored);
}

int level_json(const std::uint8_t* data, std::size_t size) {
  return load(data, size, "level.json");
}

int gltf(const std::uint8_t* data, std::size_t size) {
  const bool glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  return load(data, size, glb ? "asset.glb" : "asset.gltf");
}

int image(const std::uint8_t* data, std::size_t size) {
  Level level;
  ImageRef ref;
  ref.name = "fuzzed";
  ref.embedded.assign(data, data + size);
  level.images.push_back(ref);
  Material m;
  m.base_color_texture.image = 0;
  m.metallic_roughness_texture.image = 0;
  level.materials.push_back(m);
  try {
    const lighting::TextureSet set = lighting::TextureSet::build(level);
    (void)set;
  } catch (const InputError&) {
  }
  for (const char* mime : {"image/png", "image/jpeg", "image/x-exr"}) {
    try {
      // A smaller cap than the renderer's: decoded images stay within libFuzzer's malloc limit.
      const runtime::DecodedImage img =
          runtime::decode_image_bytes({data, size}, mime, 1024, "fuzzed");
      (void)img;
    } catch (const InputError&) {
    }
  }
  return 0;
}

}  // namespace lantern::fuzz
