// FrameLoop: frames of a HeadlessSession, read back (see frame_loop.h).
#include "tests/reliability/frame_loop.h"

#include <malloc.h>
#include <unistd.h>

#include <fstream>

#include "lighting/frame/headless_session.h"

namespace lantern::reliability {

struct FrameLoop::State {
  State(runtime::Device& device, runtime::ShaderLibrary& shaders,
        std::shared_ptr<const Level> level, const LoopOptions& o)
      : session(device, shaders, std::move(level),
                {.integrator = o.integrator,
                 .width = o.width,
                 .height = o.height,
                 .seed = o.seed,
                 .world_threads = o.world_threads}) {
    session.warm_up();
  }
  lighting::HeadlessSession session;
};

FrameLoop::FrameLoop(runtime::Device& device, runtime::ShaderLibrary& shaders,
                     std::shared_ptr<const Level> level, const LoopOptions& options)
    : state_(std::make_unique<State>(device, shaders, std::move(level), options)) {}

FrameLoop::~FrameLoop() = default;

runtime::ImageRGBA32F FrameLoop::frame() {
  runtime::ImageRGBA32F image;
  state_->session.render(state_->session.step_world(), &image);
  return image;
}

std::uint64_t resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  std::uint64_t size = 0, resident = 0;
  statm >> size >> resident;
  return resident * static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
}

std::uint64_t heap_bytes() {
  const struct mallinfo2 info = ::mallinfo2();
  return static_cast<std::uint64_t>(info.uordblks) + static_cast<std::uint64_t>(info.hblkhd);
}

}  // namespace lantern::reliability
