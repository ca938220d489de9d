// Phase-by-phase execution of the system graph on the thread pool (see scheduler.h).
#include "engine/sched/scheduler.h"

#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>

#include <fmt/format.h>

#include "engine/core/error.h"

namespace lantern {

Scheduler::Scheduler(unsigned threads) : pool_(threads) {}

SystemBuilder Scheduler::add(std::string name, Phase phase) {
  dirty_ = true;
  SystemDesc& desc = systems_.emplace_back();
  desc.name = std::move(name);
  desc.phase = phase;
  return SystemBuilder(desc);
}

void Scheduler::build() {
  if (!dirty_) return;
  graph_ = SystemGraph(systems_);
  last_ms_.assign(systems_.size(), 0.0);
  dirty_ = false;
}

const SystemGraph& Scheduler::graph() {
  build();
  return graph_;
}

void Scheduler::run(Registry& registry, const FrameTime& time) {
  build();
  // Create every declared storage up front: systems running in parallel must not grow the
  // registry's storage table.
  for (const SystemDesc& s : systems_) {
    for (const Access& a : s.reads) a.prepare(registry);
    for (const Access& a : s.writes) a.prepare(registry);
  }
  for (std::size_t p = 0; p < kPhaseCount; ++p) run_phase(registry, time, static_cast<Phase>(p));
}

void Scheduler::run_system(std::uint32_t id, Registry& registry, const FrameTime& time) {
  const auto start = std::chrono::steady_clock::now();
  systems_[id].fn(registry, time);
  last_ms_[id] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void Scheduler::run_phase(Registry& registry, const FrameTime& time, Phase phase) {
  const std::vector<std::uint32_t>& ids = graph_.phase(phase);
  if (ids.empty()) return;

  // Inline: declaration order is a topological order of the phase's graph.
  if (pool_.threads() == 1 || ids.size() == 1) {
    for (std::uint32_t id : ids) run_system(id, registry, time);
    return;
  }

  // Parallel: a system is submitted once all its predecessors finished. Counters are indexed by
  // node id; only this phase's entries are used.
  const std::vector<SystemGraph::Node>& nodes = graph_.nodes();
  std::unique_ptr<std::atomic<std::uint32_t>[]> pending(new std::atomic<std::uint32_t>[nodes.size()]);
  for (std::uint32_t id : ids) pending[id].store(static_cast<std::uint32_t>(nodes[id].after.size()));
  std::atomic<std::size_t> remaining{ids.size()};
  std::atomic<bool> failed{false};
  std::mutex error_mutex;
  std::exception_ptr error;

  std::function<void(std::uint32_t)> launch = [&](std::uint32_t id) {
    pool_.submit([&, id] {
      if (!failed.load()) {
        try {
          run_system(id, registry, time);
        } catch (...) {
          std::lock_guard lock(error_mutex);
          if (!error) error = std::current_exception();
          failed.store(true);
        }
      }
      for (std::uint32_t next : nodes[id].before) {
        if (pending[next].fetch_sub(1) == 1) launch(next);
      }
      remaining.fetch_sub(1);
    });
  };
  for (std::uint32_t id : ids) {
    if (nodes[id].after.empty()) launch(id);
  }
  pool_.help_until([&] { return remaining.load() == 0; });
  if (error) std::rethrow_exception(error);
}

std::vector<SystemTiming> Scheduler::timings() const {
  std::vector<SystemTiming> out;
  out.reserve(systems_.size());
  for (std::size_t i = 0; i < systems_.size() && i < last_ms_.size(); ++i) {
    out.push_back(SystemTiming{systems_[i].name, systems_[i].phase, last_ms_[i]});
  }
  return out;
}

double Scheduler::last_ms(std::string_view name) const {
  for (std::size_t i = 0; i < systems_.size() && i < last_ms_.size(); ++i) {
    if (systems_[i].name == name) return last_ms_[i];
  }
  throw RuntimeError(fmt::format("scheduler: no system named '{}'", name));
}

}  // namespace lantern
