#include "runtime/perf/calibration_workload.h"

#include <vector>

#include "runtime/core/device.h"
#include "runtime/gpu/bindings.h"
#include "runtime/gpu/gpu_timer.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/gpu/transfer.h"

namespace lantern::runtime {
namespace {

// Sized to take a few milliseconds on lavapipe (2 threads): long enough for 1 ns timestamps and
// scheduling noise to be small, short enough to interleave with every benchmark frame.
constexpr std::uint32_t kInvocations = 160u * 90u;
constexpr std::uint32_t kRounds = 6u;
constexpr std::uint32_t kTableEntries = 1u << 18;  // 4 MiB of vec4

struct CalibrationPush {
  std::uint32_t count;
  std::uint32_t rounds;
};

}  // namespace

CalibrationWorkload::CalibrationWorkload(Device& device, ShaderLibrary& shaders)
    : device_(device),
      pipeline_(device, shaders.load("perf/perf_calibration.comp"), {.name = "perf.calibration"}),
      table_(device, {.size = kTableEntries * 16ull,
                      .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                      .memory = MemoryUsage::DeviceLocal,
                      .name = "perf.calibration.table"}),
      result_(device, {.size = kInvocations * 16ull,
                       .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                       .memory = MemoryUsage::DeviceLocal,
                       .name = "perf.calibration.result"}) {
  std::vector<float> table(kTableEntries * 4u);
  for (std::size_t i = 0; i < table.size(); ++i) table[i] = static_cast<float>(i % 97) * 0.01f;
  upload_buffer(device, table_, std::span<const float>(table));
  pipeline_.warm_up();
}

double CalibrationWorkload::run_ms() {
  GpuTimer timer(device_, 1);
  device_.submit_and_wait([&](VkCommandBuffer cmd) {
    timer.reset(cmd);
    auto scope = timer.scope(cmd, "perf.calibration");
    Bindings bindings(pipeline_);
    bindings.buffer("calibration_table", table_).buffer("calibration_result", result_);
    pipeline_.bind(cmd, bindings);
    pipeline_.push_constants(cmd, CalibrationPush{kInvocations, kRounds});
    pipeline_.dispatch_threads(cmd, kInvocations);
  });
  return timer.resolve().at(0).ms;
}

}  // namespace lantern::runtime
