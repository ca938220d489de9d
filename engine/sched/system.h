// A system's declaration: name, phase, what it reads and writes, and its function. The scheduler
// orders systems only by these declarations, so they must be complete: a system that touches a
// component it did not declare races with the systems running beside it.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "engine/core/clock.h"
#include "engine/ecs/registry.h"
#include "engine/ecs/type_id.h"
#include "engine/sched/phase.h"

namespace lantern {

using SystemFn = std::function<void(Registry&, const FrameTime&)>;

// One declared access: a component or resource type.
struct Access {
  TypeId type = 0;
  // Creates the type's storage up front so parallel systems never grow the registry's tables.
  void (*prepare)(Registry&) = nullptr;
};

struct SystemDesc {
  std::string name;  // `module.stage`, unique in the scheduler
  Phase phase = Phase::Simulate;
  std::vector<Access> reads;
  std::vector<Access> writes;
  bool exclusive = false;  // conflicts with every other system of its phase (structural changes)
  SystemFn fn;
};

// Fluent declaration returned by Scheduler::add:
//   sched.add("anim.rotate", Phase::Simulate).reads<RotateBehaviour>().writes<Transform>()
//        .run([](Registry& r, const FrameTime& t) { ... });
class SystemBuilder {
 public:
  explicit SystemBuilder(SystemDesc& desc) : desc_(desc) {}

  template <class... T>
  SystemBuilder& reads() {
    (desc_.reads.push_back(access<T>()), ...);
    return *this;
  }
  template <class... T>
  SystemBuilder& writes() {
    (desc_.writes.push_back(access<T>()), ...);
    return *this;
  }
  // Creates/destroys entities or otherwise touches everything: runs alone within its phase.
  SystemBuilder& exclusive() {
    desc_.exclusive = true;
    return *this;
  }
  SystemBuilder& run(SystemFn fn) {
    desc_.fn = std::move(fn);
    return *this;
  }

 private:
  template <class T>
  static Access access() {
    return Access{component_id<T>(), [](Registry& r) { r.storage<std::remove_cv_t<T>>(); }};
  }

  SystemDesc& desc_;
};

}  // namespace lantern
