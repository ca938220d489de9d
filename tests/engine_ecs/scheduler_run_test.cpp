// Running the graph: conflicting systems keep declaration order, independent ones really overlap
// on several threads, errors propagate, timings are recorded, and a multi-system simulation gives
// bitwise-identical results on 1, 2 and 4 threads.
#include <gtest/gtest.h>

#include <bit>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "engine/core/rng.h"
#include "engine/sched/scheduler.h"

namespace lantern {
namespace {

struct Log {
  std::vector<std::string> lines;
};
struct A {
  float v = 0;
};
struct B {
  float v = 0;
};

TEST(SchedulerRun, ConflictingWritersRunInDeclarationOrder) {
  Scheduler s(4);
  Registry r;
  r.ctx().emplace<Log>();
  const std::vector<std::string> names{"w0", "w1", "w2", "w3", "w4"};
  for (const std::string& name : names) {
    s.add(name, Phase::Simulate).writes<Log>().run([name](Registry& reg, const FrameTime&) {
      std::this_thread::sleep_for(std::chrono::microseconds(200));
      reg.ctx().get<Log>().lines.push_back(name);
    });
    // Independent filler so the pool has parallel work beside the chain.
    s.add(name + ".free", Phase::Simulate).writes<A>().run([](Registry&, const FrameTime&) {});
  }
  // Filler systems all write A, so they form their own chain; neither chain orders the other.
  EXPECT_FALSE(s.graph().ordered("w0", "w0.free"));
  for (int frame = 0; frame < 20; ++frame) {
    r.ctx().get<Log>().lines.clear();
    s.run(r, FrameTime{});
    EXPECT_EQ(r.ctx().get<Log>().lines, names) << "frame " << frame;
  }
}

// Two systems that can only both finish if they run at the same time: each waits (bounded) for
// the other to arrive. Serial execution makes the first wait time out, which fails the test.
TEST(SchedulerRun, IndependentSystemsOverlapOnSeveralThreads) {
  struct Rendezvous {
    std::mutex mutex;
    std::condition_variable cv;
    int arrived = 0;
    bool met[2] = {false, false};
  } rv;
  const auto meet = [&rv](int who) {
    std::unique_lock lock(rv.mutex);
    ++rv.arrived;
    rv.cv.notify_all();
    rv.met[who] = rv.cv.wait_for(lock, std::chrono::seconds(5), [&] { return rv.arrived >= 2; });
  };
  Scheduler s(2);
  Registry r;
  s.add("left", Phase::Simulate).writes<A>().run([&](Registry&, const FrameTime&) { meet(0); });
  s.add("right", Phase::Simulate).writes<B>().run([&](Registry&, const FrameTime&) { meet(1); });
  s.run(r, FrameTime{});
  EXPECT_TRUE(rv.met[0]);
  EXPECT_TRUE(rv.met[1]);
}

TEST(SchedulerRun, OneThreadRunsInlineOnCaller) {
  Scheduler s(1);
  Registry r;
  std::vector<std::thread::id> ids;
  s.add("x", Phase::Simulate).writes<A>().run([&](Registry&, const FrameTime&) { ids.push_back(std::this_thread::get_id()); });
  s.add("y", Phase::Render).writes<B>().run([&](Registry&, const FrameTime&) { ids.push_back(std::this_thread::get_id()); });
  s.run(r, FrameTime{});
  EXPECT_EQ(ids, (std::vector<std::thread::id>{std::this_thread::get_id(), std::this_thread::get_id()}));
}

TEST(SchedulerRun, SystemErrorPropagatesAndStopsLaterPhases) {
  for (unsigned threads : {1u, 2u}) {
    Scheduler s(threads);
    Registry r;
    bool later_ran = false;
    s.add("boom", Phase::Simulate).writes<A>().run([](Registry&, const FrameTime&) { throw RuntimeError("boom failed"); });
    s.add("side", Phase::Simulate).writes<B>().run([](Registry&, const FrameTime&) {});
    s.add("later", Phase::Extract).reads<A>().run([&](Registry&, const FrameTime&) { later_ran = true; });
    EXPECT_THROW(s.run(r, FrameTime{}), RuntimeError) << threads;
    EXPECT_FALSE(later_ran) << threads;
  }
}

TEST(SchedulerRun, RecordsPerSystemTimingsAndPreparesStorages) {
  Scheduler s(2);
  Registry r;
  s.add("slow", Phase::Simulate).writes<A>().run([](Registry&, const FrameTime&) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  });
  s.add("fast", Phase::Simulate).reads<B>().run([](Registry&, const FrameTime&) {});
  s.run(r, FrameTime{});
  EXPECT_GE(s.last_ms("slow"), 4.0);
  EXPECT_LT(s.last_ms("fast"), s.last_ms("slow"));
  EXPECT_EQ(s.timings().size(), 2u);
  EXPECT_THROW(s.last_ms("nope"), RuntimeError);
  EXPECT_NE(r.find_storage<A>(), nullptr);
  EXPECT_NE(r.find_storage<B>(), nullptr);
}

// --- determinism: a small world updated by several systems ------------------------------------

struct Position {
  float x = 0, y = 0, z = 0;
};
struct Velocity {
  float x = 0, y = 0, z = 0;
};
struct Spin {
  float angle = 0, rate = 0;
};
struct Glow {
  float value = 0;
};
struct Wind {
  float x = 0, z = 0;
};
struct Stats {
  float energy = 0;  // a float sum: wrong order would change its bits
  std::uint64_t hash = 1469598103934665603ull;
};
struct WorldRng {
  Rng rng;
};

std::uint64_t fold(std::uint64_t h, float f) { return (h ^ std::bit_cast<std::uint32_t>(f)) * 1099511628211ull; }

void spawn(Registry& r, Rng& rng) {
  const Entity e = r.create();
  r.emplace<Position>(e, rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
  r.emplace<Velocity>(e, rng.uniform(-1, 1), 0.0f, rng.uniform(-1, 1));
  if (rng.bounded(2) == 0) r.emplace<Spin>(e, 0.0f, rng.uniform(-3, 3));
  if (rng.bounded(3) == 0) r.emplace<Glow>(e, 0.5f);
}

void declare_world(Scheduler& s) {
  s.add("input.wind", Phase::Input).reads<WorldRng>().writes<Wind>().run([](Registry& r, const FrameTime& t) {
    Rng rng = r.ctx().get<WorldRng>().rng.split(t.frame_index);
    r.ctx().get<Wind>() = Wind{rng.uniform(-0.5f, 0.5f), rng.uniform(-0.5f, 0.5f)};
  });
  s.add("sim.accelerate", Phase::Simulate).reads<Wind, WorldRng>().writes<Velocity>().run([](Registry& r, const FrameTime& t) {
    const Wind w = r.ctx().get<Wind>();
    const Rng base = r.ctx().get<WorldRng>().rng.split(hash_name("sim.accelerate") ^ t.frame_index);
    r.view<Velocity>().each([&](Entity e, Velocity& v) {
      Rng rng = base.split(e.bits());
      v.x += (w.x + rng.uniform(-0.1f, 0.1f)) * float(t.dt);
      v.z += (w.z + rng.uniform(-0.1f, 0.1f)) * float(t.dt);
      v.y -= 9.81f * float(t.dt);
    });
  });
  s.add("sim.drag", Phase::Simulate).writes<Velocity>().run([](Registry& r, const FrameTime& t) {
    const float k = 1.0f - 0.3f * float(t.dt);
    r.view<Velocity>().each([k](Velocity& v) {
      v.x *= k;
      v.y *= k;
      v.z *= k;
    });
  });
  s.add("sim.spin", Phase::Simulate).writes<Spin>().run([](Registry& r, const FrameTime& t) {
    r.view<Spin>().each([&](Spin& sp) { sp.angle = std::fmod(sp.angle + sp.rate * float(t.dt), 6.2831853f); });
  });
  s.add("sim.glow", Phase::Simulate).reads<Spin>().writes<Glow>().run([](Registry& r, const FrameTime&) {
    r.view<Glow, const Spin>().each([](Glow& g, const Spin& sp) { g.value = 0.5f + 0.5f * std::sin(sp.angle); });
  });
  s.add("sim.respawn", Phase::Simulate).exclusive().run([](Registry& r, const FrameTime& t) {
    if (t.frame_index % 5 != 4) return;
    Rng rng = r.ctx().get<WorldRng>().rng.split(t.frame_index * 31 + 7);
    const auto entities = r.storage<Position>().entities();
    const Entity victim = entities[rng.bounded(static_cast<std::uint32_t>(entities.size()))];
    r.destroy(victim);
    spawn(r, rng);
  });
  s.add("xform.integrate", Phase::Transform).reads<Velocity>().writes<Position>().run([](Registry& r, const FrameTime& t) {
    const float dt = float(t.dt);
    r.view<Position, const Velocity>().each([dt](Position& p, const Velocity& v) {
      p.x += v.x * dt;
      p.y = std::max(p.y + v.y * dt, -10.0f);
      p.z += v.z * dt;
    });
  });
  s.add("xform.spin_energy", Phase::Transform).reads<Spin>().writes<Stats>().run([](Registry& r, const FrameTime&) {
    float e = 0;
    r.view<const Spin>().each([&e](const Spin& sp) { e += sp.rate * sp.rate; });
    r.ctx().get<Stats>().energy += e;
  });
  s.add("extract.hash", Phase::Extract).reads<Position, Glow>().writes<Stats>().run([](Registry& r, const FrameTime&) {
    Stats& st = r.ctx().get<Stats>();
    r.view<const Position>().each([&st](const Position& p) { st.hash = fold(fold(fold(st.hash, p.x), p.y), p.z); });
    r.view<const Glow>().each([&st](const Glow& g) { st.hash = fold(st.hash, g.value); });
  });
}

struct WorldResult {
  std::vector<std::uint32_t> bits;  // every component float and entity handle, in storage order
  std::uint64_t hash = 0;
  std::uint32_t energy_bits = 0;
};

WorldResult simulate(unsigned threads) {
  Registry r;
  r.ctx().emplace<WorldRng>(Rng(2024));
  r.ctx().emplace<Wind>();
  r.ctx().emplace<Stats>();
  Rng setup(99);
  for (int i = 0; i < 20000; ++i) spawn(r, setup);  // big enough that parallel systems overlap
  Scheduler s(threads);
  declare_world(s);
  FixedClock clock(1.0 / 60.0);
  for (int frame = 0; frame < 100; ++frame) s.run(r, clock.tick());

  WorldResult out;
  const auto push = [&out](auto storage_values, auto entities) {
    for (Entity e : entities) out.bits.push_back(e.bits());
    for (const auto& v : storage_values) {
      const auto* f = reinterpret_cast<const float*>(&v);
      for (std::size_t k = 0; k < sizeof(v) / sizeof(float); ++k) out.bits.push_back(std::bit_cast<std::uint32_t>(f[k]));
    }
  };
  push(r.storage<Position>().values(), r.storage<Position>().entities());
  push(r.storage<Velocity>().values(), r.storage<Velocity>().entities());
  push(r.storage<Spin>().values(), r.storage<Spin>().entities());
  push(r.storage<Glow>().values(), r.storage<Glow>().entities());
  out.hash = r.ctx().get<Stats>().hash;
  out.energy_bits = std::bit_cast<std::uint32_t>(r.ctx().get<Stats>().energy);
  return out;
}

testing::AssertionResult same_world(const WorldResult& a, const WorldResult& b) {
  if (a.bits.size() != b.bits.size()) return testing::AssertionFailure() << "component counts differ";
  for (std::size_t i = 0; i < a.bits.size(); ++i) {
    if (a.bits[i] != b.bits[i]) return testing::AssertionFailure() << "first differing word at " << i;
  }
  if (a.hash != b.hash || a.energy_bits != b.energy_bits) return testing::AssertionFailure() << "stats differ";
  return testing::AssertionSuccess();
}

TEST(SchedulerRun, BitwiseIdenticalAcrossThreadCounts) {
  const WorldResult one = simulate(1);
  ASSERT_GT(one.bits.size(), 10000u);
  // The world really evolved (guards against a simulation that ignores its systems).
  EXPECT_NE(one.hash, Stats{}.hash);
  EXPECT_NE(one.energy_bits, 0u);
  EXPECT_TRUE(same_world(simulate(2), one));
  EXPECT_TRUE(same_world(simulate(4), one));
}

}  // namespace
}  // namespace lantern
