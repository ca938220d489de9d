// A headless frame loop for the reliability tests: the frames of a lighting::HeadlessSession (the
// one frame loop, with the World's thread count exposed; render_offline always uses 1), each
// read back as linear radiance.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "engine/scene/level.h"
#include "lighting/integrators/integrator_registry.h"
#include "runtime/image/image.h"

namespace lantern::runtime {
class Device;
class ShaderLibrary;
}  // namespace lantern::runtime

namespace lantern::reliability {

struct LoopOptions {
  lighting::IntegratorConfig integrator;
  std::uint32_t width = 64;
  std::uint32_t height = 36;
  std::uint32_t seed = 1;
  unsigned world_threads = 1;
};

class FrameLoop {
 public:
  FrameLoop(runtime::Device& device, runtime::ShaderLibrary& shaders,
            std::shared_ptr<const Level> level, const LoopOptions& options);
  ~FrameLoop();
  FrameLoop(const FrameLoop&) = delete;
  FrameLoop& operator=(const FrameLoop&) = delete;

  // Steps the world one frame, renders it and returns the linear radiance.
  runtime::ImageRGBA32F frame();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// Resident set size of this process in bytes (/proc/self/statm).
std::uint64_t resident_bytes();

// Bytes the process holds allocated through malloc (new, the driver's allocations included):
// glibc's mallinfo2, in-use chunks of every arena plus mmapped chunks. Exact to the chunk, unlike
// the resident set, which moves in pages and keeps freed memory.
std::uint64_t heap_bytes();

}  // namespace lantern::reliability
