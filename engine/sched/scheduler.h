// The frame scheduler: systems are declared with a name, a phase and their reads/writes; the
// scheduler derives the dependency graph (system_graph.h) and runs each phase on a worker pool,
// independent systems in parallel, conflicting ones in declaration order. Because every pair
// that could observe each other's writes is ordered the same way whatever the thread count,
// results are bitwise identical for 1 and N threads (given deterministic systems).
#pragma once

#include <deque>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/clock.h"
#include "engine/ecs/registry.h"
#include "engine/sched/system.h"
#include "engine/sched/system_graph.h"
#include "engine/sched/thread_pool.h"

namespace lantern {

struct SystemTiming {
  std::string_view name;
  Phase phase;
  double ms;  // CPU wall time of the system's function in the last frame
};

class Scheduler {
 public:
  // `threads` = 1 runs every system inline on the caller, in declaration order.
  explicit Scheduler(unsigned threads = 1);

  // Declares a system; finish the declaration with the returned builder. The graph is rebuilt
  // (and the declarations validated) before the next frame.
  SystemBuilder add(std::string name, Phase phase);

  // Validates declarations and derives the graph now (run() does it when needed). Throws
  // RuntimeError naming the offending system.
  void build();
  const SystemGraph& graph();
  std::string describe() { return graph().describe(); }

  // Runs one frame: all phases in order, each a barrier. Rethrows the first exception a system
  // threw, after the phase has drained (systems not yet started in that phase are skipped).
  void run(Registry& registry, const FrameTime& time);

  std::vector<SystemTiming> timings() const;
  // Last-frame time of one system in ms; throws if no system has that name.
  double last_ms(std::string_view name) const;
  unsigned threads() const { return pool_.threads(); }

 private:
  void run_phase(Registry& registry, const FrameTime& time, Phase phase);
  void run_system(std::uint32_t id, Registry& registry, const FrameTime& time);

  std::deque<SystemDesc> systems_;  // deque: builders keep valid references while others are added
  SystemGraph graph_;
  bool dirty_ = true;
  std::vector<double> last_ms_;
  ThreadPool pool_;
};

}  // namespace lantern
