// The dispatch shape of the per-pixel compute passes. Their workgroups take a shape per device
// (pixel_group_shape, shared/pixel_groups.h: rows of 64 on CPU devices, 8x8 on GPUs). The tile
// passes (integrators.baseline, integrators.reference, restir.*; restir.initial keeps 8x8 on every
// device) run one workgroup per tile of their pipeline's shape, visited in a shuffled order
// g -> g * stride mod count so neighbouring workgroups land far apart and both lavapipe threads
// get a mix of sky and geometry (shared/PLATFORM.md); on CPU devices restir.temporal and
// restir.spatial walk interleaved bands of tile rows instead (tile_bands), which keeps the
// neighbours they read in each thread's cache. The others (denoise.*, upscale.temporal) map
// threads to pixels in dispatch order.
#pragma once

#include <cstdint>

#include <glm/vec2.hpp>

#include "runtime/gpu/compute_pipeline.h"
#include "runtime/runtime_fwd.h"

namespace lantern::lighting {

// Number of tiles of shape `tile` covering width x height.
std::uint32_t tile_count(std::uint32_t width, std::uint32_t height, glm::uvec2 tile);
// ... of `pipeline`'s workgroup shape (after specialisation): the workgroups a tile pass
// dispatches.
std::uint32_t tile_count(std::uint32_t width, std::uint32_t height,
                         const runtime::ComputePipeline& pipeline);

// A stride near count / golden ratio that is coprime to `count` (so the order is a permutation);
// 1 when the product could overflow 32 bits.
std::uint32_t tile_stride(std::uint32_t count);

// The interleaved bands of tile rows restir.temporal and restir.spatial walk
// (shared/pixel_groups.h, pixel_tile_origin): on a CPU device the number of threads lavapipe
// splits a dispatch between (counted as llvmpipe does: the CPUs this process may use, or
// LP_NUM_THREADS; 1 to 32), 0 (the stride's shuffle) on a GPU.
std::uint32_t tile_bands(bool cpu_device);

// The workgroup shape of the per-pixel passes (shared/pixel_groups.h): rows of
// kPixelGroupCpuWidth threads on a CPU device, kPixelGroupGpuSide squared on a GPU.
glm::uvec2 pixel_group_shape(bool cpu_device);
// The specialisation constants that give a per-pixel pass's pipeline the workgroup shape
// `shape`, or `device`'s (pixel_group_shape).
runtime::SpecConstants pixel_group_constants(glm::uvec2 shape);
runtime::SpecConstants pixel_group_constants(const runtime::Device& device);

}  // namespace lantern::lighting
