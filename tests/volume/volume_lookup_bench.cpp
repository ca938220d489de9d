// Benchmark, not a test: which GPU layout of a volume's grid looks densities up faster on this
// device — the project's bricks (9^3 floats per 8^3 cell, apron included) with a majorant cell
// box (runtime/volume/volume_grid.h, what the volume passes read) or NanoVDB's tree (nanovdb::openToNanoVDB on the same OpenVDB
// grid, read through PNanoVDB.h in GLSL with its value accessor). For each volume of a level:
// 16384 rays x 256 trilinear lookups half a voxel apart (the access pattern of tracking), median
// GPU ms of 9 alternating dispatches per layout, the memory of each, and a check that both
// layouts return the same densities.
// Usage: volume_lookup_bench [LEVEL] (default harbour_fog)
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <nanovdb/util/OpenToNanoVDB.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "engine/level/level_loader.h"
#include "runtime/core/device.h"
#include "runtime/gpu/bindings.h"
#include "runtime/gpu/buffer.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/gpu/gpu_timer.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/gpu/transfer.h"
#include "runtime/volume/vdb_reader.h"
#include "runtime/volume/volume_generator.h"
#include "runtime/volume/volume_set.h"

using namespace lantern;

namespace {

constexpr std::uint32_t kThreads = 16384;
constexpr std::uint32_t kSteps = 256;

struct Push {
  glm::vec4 box_min;
  glm::vec4 box_max;
  std::uint32_t steps;
  std::uint32_t threads;
};

template <class T>
runtime::Buffer storage(runtime::Device& device, std::span<const T> values, const char* name) {
  runtime::Buffer b(device, {.size = std::max<std::size_t>(values.size_bytes(), 16),
                             .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                             .memory = runtime::MemoryUsage::DeviceLocal,
                             .name = name});
  if (!values.empty()) runtime::upload_buffer(device, b, values);
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  const Level level = load_level_argument(argc > 1 ? argv[1] : "harbour_fog");
  const std::vector<runtime::VolumeGrid> grids = runtime::load_volume_grids(level);
  if (grids.empty()) {
    std::fprintf(stderr, "volume_lookup_bench: level '%s' has no volumes\n", level.name.c_str());
    return 2;
  }
  runtime::initialize_openvdb();
  runtime::Device device(runtime::DeviceOptions{});
  runtime::ShaderLibrary shaders;
  runtime::GpuTimer timer(device, 4);
  std::printf("%s on %s: %u rays x %u trilinear lookups per layout\n", level.name.c_str(),
              device.properties().deviceName, kThreads, kSteps);
  for (std::size_t g = 0; g < grids.size(); ++g) {
    const runtime::VolumeGrid& grid = grids[g];
    const Volume& volume = level.volumes[g];
    // NanoVDB from the same file and grid the loader read.
    openvdb::io::File file(grid.file.string());
    file.open();
    const auto base = file.readGrid(grid.grid_name);
    file.close();
    const auto handle = nanovdb::openToNanoVDB(openvdb::gridPtrCast<openvdb::FloatGrid>(base));
    const std::span<const std::uint32_t> nano_words(
        reinterpret_cast<const std::uint32_t*>(handle.data()), handle.size() / 4);
    const gpu::GpuVolume record = grid.lookup_record();
    runtime::Buffer nano = storage(device, nano_words, "bench.nanovdb");
    runtime::Buffer cells = storage(device, std::span(grid.cells), "bench.cells");
    runtime::Buffer values = storage(device, std::span(grid.values), "bench.values");
    runtime::Buffer rec = storage(device, std::span(&record, 1), "bench.record");
    runtime::Buffer out(device, {.size = kThreads * sizeof(float),
                                 .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                 .memory = runtime::MemoryUsage::Readback,
                                 .name = "bench.out"});
    const Push push{glm::vec4(glm::vec3(grid.active_min), 0.0f),
                    glm::vec4(glm::vec3(grid.active_max), 0.0f), kSteps, kThreads};
    std::vector<std::unique_ptr<runtime::ComputePipeline>> pipelines;
    for (const bool nanovdb : {false, true}) {
      pipelines.push_back(std::make_unique<runtime::ComputePipeline>(
          device, shaders.load("tests/volume_lookup_bench.comp"),
          runtime::ComputePipelineDesc{
              .name = "bench.volume_lookup",
              .constants = runtime::SpecConstants().set("kNanoVdb", nanovdb)}));
    }
    std::vector<double> ms[2];
    std::vector<float> sums[2];
    for (int run = 0; run < 10; ++run) {
      for (int layout = 0; layout < 2; ++layout) {  // alternating A B
        runtime::ComputePipeline& p = *pipelines[static_cast<std::size_t>(layout)];
        device.submit_and_wait([&](VkCommandBuffer cmd) {
          timer.reset(cmd);
          timer.begin(cmd, "lookup");
          p.bind(cmd, runtime::Bindings(p)
                          .buffer("NanoGrid", nano)
                          .buffer("bench_cells", cells)
                          .buffer("bench_values", values)
                          .buffer("bench_record", rec)
                          .buffer("bench_out", out));
          p.push_constants(cmd, push);
          p.dispatch_threads(cmd, kThreads);
          timer.end(cmd);
        });
        if (run > 0) ms[layout].push_back(timer.resolve().at(0).ms);  // run 0 pays the JIT
        if (run == 0) sums[layout] = runtime::read_buffer<float>(device, out);
      }
    }
    double worst = 0.0;
    for (std::uint32_t i = 0; i < kThreads; ++i) {
      const double a = sums[0][i], b = sums[1][i];
      worst = std::max(worst, std::abs(a - b) / std::max(std::abs(a), 1e-6));
    }
    for (auto& m : ms) std::sort(m.begin(), m.end());
    const double bricks_ms = ms[0][ms[0].size() / 2];
    const double nano_ms = ms[1][ms[1].size() / 2];
    std::printf(
        "%-12s %7llu active voxels  bricks %7.2f ms (%.1f MiB)  nanovdb %7.2f ms (%.1f MiB)  "
        "nanovdb/bricks %.2fx  worst relative difference %.1e\n",
        volume.name.c_str(), static_cast<unsigned long long>(grid.active_voxels), bricks_ms,
        double(grid.bytes()) / 1048576.0, nano_ms, double(handle.size()) / 1048576.0,
        nano_ms / bricks_ms, worst);
  }
  return 0;
}
