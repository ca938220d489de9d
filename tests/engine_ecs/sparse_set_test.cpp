// Sparse-set invariants under random add/remove/update, cross-checked against a std::map model.
#include <gtest/gtest.h>

#include <map>

#include "engine/core/rng.h"
#include "engine/ecs/registry.h"

namespace lantern {
namespace {

struct Value {
  std::uint64_t v = 0;
};

void expect_matches(Registry& r, const std::map<std::uint32_t, std::uint64_t>& model) {
  const Storage<Value>& s = r.storage<Value>();
  ASSERT_EQ(s.size(), model.size());
  ASSERT_EQ(s.entities().size(), s.values().size());
  // Every dense entry maps back to itself and holds the model's value.
  for (std::size_t i = 0; i < s.size(); ++i) {
    const Entity e = s.entities()[i];
    ASSERT_EQ(s.index_of(e), i);
    const auto it = model.find(e.bits());
    ASSERT_NE(it, model.end());
    ASSERT_EQ(s.values()[i].v, it->second);
  }
  for (const auto& [bits, v] : model) {
    ASSERT_EQ(r.get<Value>(Entity::from_bits(bits)).v, v);
  }
}

TEST(SparseSet, RandomOperationsMatchMapModel) {
  Registry r;
  Rng rng(7);
  std::vector<Entity> live;
  std::vector<Entity> dead;
  std::map<std::uint32_t, std::uint64_t> model;  // entity bits -> value of entities with Value

  for (int step = 0; step < 20000; ++step) {
    const std::uint32_t op = rng.bounded(6);
    if (op == 0 || live.empty()) {
      live.push_back(r.create());
    } else {
      const std::size_t k = rng.bounded(static_cast<std::uint32_t>(live.size()));
      const Entity e = live[k];
      const bool has = model.count(e.bits()) != 0;
      switch (op) {
        case 1:
        case 2:  // add or replace
          if (has) {
            r.replace<Value>(e, Value{rng.next_u32()});
          } else {
            r.emplace<Value>(e, rng.next_u32());
          }
          model[e.bits()] = r.get<Value>(e).v;
          break;
        case 3:
          EXPECT_EQ(r.remove<Value>(e), has);
          model.erase(e.bits());
          break;
        case 4:
          r.destroy(e);
          model.erase(e.bits());
          dead.push_back(e);
          live[k] = live.back();
          live.pop_back();
          break;
        default:
          if (has) r.patch<Value>(e, [](Value& v) { v.v += 1; });
          if (has) model[e.bits()] += 1;
          break;
      }
    }
    if (step % 500 == 0) expect_matches(r, model);
  }
  expect_matches(r, model);
  EXPECT_EQ(r.alive(), live.size());
  for (Entity e : dead) {
    EXPECT_FALSE(r.valid(e));
    EXPECT_EQ(r.try_get<Value>(e), nullptr);
  }
}

TEST(SparseSet, RemoveSwapsLastIntoHole) {
  Registry r;
  const Entity a = r.create();
  const Entity b = r.create();
  const Entity c = r.create();
  r.emplace<Value>(a, 1u);
  r.emplace<Value>(b, 2u);
  r.emplace<Value>(c, 3u);
  r.remove<Value>(a);
  const Storage<Value>& s = r.storage<Value>();
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s.entities()[0], c);
  EXPECT_EQ(s.values()[0].v, 3u);
  EXPECT_EQ(r.get<Value>(b).v, 2u);
  EXPECT_FALSE(r.remove<Value>(a));
}

}  // namespace
}  // namespace lantern
