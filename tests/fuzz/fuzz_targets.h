// The loader fuzz targets (issue 7): each writes the input to a scratch file and loads it through
// the real entry point (lantern::load_level). Bad input must end in lantern::InputError; any other
// exception escapes (an abort = a crash for libFuzzer and a failure for the replay test), and
// ASan/UBSan/libFuzzer catch memory errors, hangs (-timeout) and absurd allocations
// (-malloc_limit_mb). Used by the libFuzzer executables (LANTERN_FUZZ=ON, clang) and by
// fuzz_replay_test (every build), which replays the seed corpus and tests/fuzz/regressions.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>

namespace lantern::fuzz {

// A per-process scratch directory holding copies of the level test assets (glTF files, sky.hdr,
// budget.json from `assets`) so fuzzed levels can reference real files. Call once.
void init(const std::filesystem::path& assets);
// Removes the scratch directory (the replay test; libFuzzer processes leave theirs in $TMPDIR).
void cleanup();

// A JSON level (scratch/level.json). Returns 0.
int level_json(const std::uint8_t* data, std::size_t size);
// A glTF file: .glb if the input starts with the GLB magic "glTF", else .gltf. Returns 0.
int gltf(const std::uint8_t* data, std::size_t size);
// An embedded material image (issue 15): the bytes as a level's base-colour and
// metallic-roughness image through lighting::TextureSet::build (format sniffed from the
// signature, OpenImageIO decode, size cap, sRGB decode, mip chain), then as a PNG, JPEG and EXR
// by MIME type straight through runtime::decode_image_bytes. Returns 0.
int image(const std::uint8_t* data, std::size_t size);
// An OpenVDB file (issue 14): the bytes as a scratch .vdb through runtime::read_vdb_grid (open,
// grid lookup, type and transform checks, voxel caps, value checks, bricks and majorant grid).
// In fuzz_vdb_target.cpp: it needs only the runtime, so its libFuzzer build stays small (no
// init() needed). Returns 0.
int vdb(const std::uint8_t* data, std::size_t size);

}  // namespace lantern::fuzz
