// ECS micro-benchmarks: a two-component view over 10^6 entities (Position += Velocity * dt), and
// entity create/destroy throughput. Run from a Release build: build/bin/ecs_bench.
#include <benchmark/benchmark.h>

#include <vector>

#include "engine/ecs/registry.h"

namespace lantern {
namespace {

struct Position {
  float x = 0, y = 0, z = 0;
};
struct Velocity {
  float x = 0, y = 0, z = 0;
};

void BM_ViewPositionVelocity(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  Registry r;
  for (std::size_t i = 0; i < n; ++i) {
    const Entity e = r.create();
    r.emplace<Position>(e, float(i), 0.0f, 0.0f);
    r.emplace<Velocity>(e, 1.0f, 2.0f, 3.0f);
  }
  const float dt = 1.0f / 60.0f;
  for (auto _ : state) {
    r.view<Position, const Velocity>().each([dt](Position& p, const Velocity& v) {
      p.x += v.x * dt;
      p.y += v.y * dt;
      p.z += v.z * dt;
    });
    benchmark::DoNotOptimize(r.storage<Position>().values().data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * n));
  state.counters["ns_per_entity"] = benchmark::Counter(
      static_cast<double>(state.iterations() * n), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_ViewPositionVelocity)->Arg(1'000'000)->Unit(benchmark::kMillisecond);

// Half the entities lack Velocity: the view probes and skips them.
void BM_ViewHalfMatching(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  Registry r;
  for (std::size_t i = 0; i < n; ++i) {
    const Entity e = r.create();
    r.emplace<Position>(e);
    if (i % 2 == 0) r.emplace<Velocity>(e, 1.0f, 2.0f, 3.0f);
  }
  for (auto _ : state) {
    r.view<const Velocity, Position>().each([](const Velocity& v, Position& p) { p.x += v.x; });
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * n));
}
BENCHMARK(BM_ViewHalfMatching)->Arg(1'000'000)->Unit(benchmark::kMillisecond);

void BM_CreateDestroy(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  Registry r;
  std::vector<Entity> entities(n);
  for (auto _ : state) {
    for (Entity& e : entities) {
      e = r.create();
      r.emplace<Position>(e);
      r.emplace<Velocity>(e);
    }
    for (Entity e : entities) r.destroy(e);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * n));
  state.counters["ns_per_entity"] = benchmark::Counter(
      static_cast<double>(state.iterations() * n), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_CreateDestroy)->Arg(100'000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace lantern

BENCHMARK_MAIN();
