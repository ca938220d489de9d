// Views visit exactly the entities that have every requested component, from the smallest set.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "engine/ecs/registry.h"

namespace lantern {
namespace {

struct Position {
  float x = 0;
};
struct Velocity {
  float x = 0;
};
struct Frozen {};

TEST(View, VisitsIntersectionOnly) {
  Registry r;
  std::set<std::uint32_t> expected;
  for (int i = 0; i < 100; ++i) {
    const Entity e = r.create();
    if (i % 2 == 0) r.emplace<Position>(e, float(i));
    if (i % 3 == 0) r.emplace<Velocity>(e, 1.0f);
    if (i % 2 == 0 && i % 3 == 0) expected.insert(e.bits());
  }
  std::set<std::uint32_t> visited;
  r.view<Position, const Velocity>().each([&](Entity e, Position& p, const Velocity& v) {
    EXPECT_TRUE(visited.insert(e.bits()).second);
    EXPECT_EQ(p.x, float(e.index()));
    p.x += v.x;
  });
  EXPECT_EQ(visited, expected);
  for (std::uint32_t bits : expected) EXPECT_EQ(r.get<Position>(Entity::from_bits(bits)).x, float(Entity::from_bits(bits).index()) + 1.0f);
}

TEST(View, IteratesTheSmallestSet) {
  Registry r;
  for (int i = 0; i < 50; ++i) r.emplace<Position>(r.create());
  const Entity only = r.create();
  r.emplace<Position>(only);
  r.emplace<Velocity>(only);
  auto view = r.view<Position, Velocity>();
  EXPECT_EQ(view.size_hint(), 1u);
  int calls = 0;
  view.each([&](Entity e, Position&, Velocity&) {
    EXPECT_EQ(e, only);
    ++calls;
  });
  EXPECT_EQ(calls, 1);
}

TEST(View, RemovingCurrentEntityDuringIterationIsSafe) {
  Registry r;
  for (int i = 0; i < 64; ++i) {
    const Entity e = r.create();
    r.emplace<Position>(e, float(i));
    if (i % 4 == 0) r.emplace<Frozen>(e);
  }
  int visited = 0;
  r.view<Position>().each([&](Entity e, Position&) {
    ++visited;
    if (r.all_of<Frozen>(e)) r.destroy(e);
  });
  EXPECT_EQ(visited, 64);
  EXPECT_EQ(r.storage<Position>().size(), 48u);
  EXPECT_EQ(r.storage<Frozen>().size(), 0u);
}

TEST(View, EmptyWhenAnyStorageIsEmpty) {
  Registry r;
  for (int i = 0; i < 10; ++i) r.emplace<Position>(r.create());
  int calls = 0;
  r.view<Position, Velocity>().each([&](Position&, Velocity&) { ++calls; });
  EXPECT_EQ(calls, 0);
  EXPECT_TRUE(r.view<Position>().contains(r.storage<Position>().entities()[0]));
}

}  // namespace
}  // namespace lantern
