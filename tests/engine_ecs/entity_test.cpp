// Entity lifetime: generations make stale handles detectable, slots are reused, and a slot whose
// generation would wrap is retired instead of aliasing old handles.
#include <gtest/gtest.h>

#include <set>

#include "engine/ecs/registry.h"

namespace lantern {
namespace {

struct Health {
  int hp = 0;
};

TEST(Entity, StaleHandleIsDetectedAfterSlotReuse) {
  Registry r;
  const Entity a = r.create();
  r.emplace<Health>(a, 10);
  r.destroy(a);
  EXPECT_FALSE(r.valid(a));

  const Entity b = r.create();  // reuses a's slot
  ASSERT_EQ(b.index(), a.index());
  EXPECT_NE(b.generation(), a.generation());
  EXPECT_TRUE(r.valid(b));
  r.emplace<Health>(b, 99);

  // The stale handle never reaches b's data.
  EXPECT_THROW(r.get<Health>(a), RuntimeError);
  EXPECT_EQ(r.try_get<Health>(a), nullptr);
  EXPECT_FALSE(r.all_of<Health>(a));
  EXPECT_THROW(r.emplace<Health>(a, 1), RuntimeError);
  EXPECT_THROW(r.remove<Health>(a), RuntimeError);
  EXPECT_THROW(r.destroy(a), RuntimeError);
  EXPECT_EQ(r.get<Health>(b).hp, 99);

  const Registry& cr = r;  // the const path checks the same way, without creating storages
  EXPECT_THROW(cr.get<Health>(a), RuntimeError);
  EXPECT_EQ(cr.try_get<Health>(a), nullptr);
  EXPECT_EQ(cr.get<Health>(b).hp, 99);
}

TEST(Entity, ErrorMessageNamesEntityAndComponent) {
  Registry r;
  const Entity e = r.create();
  try {
    r.get<Health>(e);
    FAIL() << "expected an error";
  } catch (const RuntimeError& err) {
    const std::string what = err.what();
    EXPECT_NE(what.find("Health"), std::string::npos) << what;
    EXPECT_NE(what.find(describe(e)), std::string::npos) << what;
  }
}

TEST(Entity, NullHandleIsNeverValid) {
  Registry r;
  r.create();
  EXPECT_FALSE(r.valid(Entity::null()));
  EXPECT_FALSE(static_cast<bool>(Entity::null()));
  EXPECT_THROW(r.get<Health>(Entity::null()), RuntimeError);
  EXPECT_THROW(r.destroy(Entity::null()), RuntimeError);
}

TEST(Entity, GenerationExhaustionRetiresTheSlot) {
  Registry r;
  std::set<std::uint32_t> seen_bits;
  Entity e = r.create();
  const std::uint32_t slot = e.index();
  std::vector<Entity> old;
  // Cycle one slot through every generation it can have.
  for (std::uint32_t g = 0; g < Entity::kMaxGeneration; ++g) {
    ASSERT_EQ(e.index(), slot);
    ASSERT_EQ(e.generation(), g);
    EXPECT_TRUE(seen_bits.insert(e.bits()).second);
    old.push_back(e);
    r.destroy(e);
    e = r.create();
  }
  // The slot is used up: the next entity lives elsewhere and no old handle became valid again.
  EXPECT_NE(e.index(), slot);
  for (Entity o : old) EXPECT_FALSE(r.valid(o));
  EXPECT_TRUE(r.valid(e));
  EXPECT_EQ(r.alive(), 1u);
}

TEST(Entity, DestroyRemovesAllComponents) {
  struct Tag {};
  Registry r;
  const Entity a = r.create();
  const Entity b = r.create();
  r.emplace<Health>(a, 1);
  r.emplace<Tag>(a);
  r.emplace<Health>(b, 2);
  r.destroy(a);
  EXPECT_EQ(r.storage<Health>().size(), 1u);
  EXPECT_EQ(r.storage<Tag>().size(), 0u);
  EXPECT_EQ(r.get<Health>(b).hp, 2);
  EXPECT_EQ(r.alive(), 1u);
}

TEST(Entity, ComponentIdsAreStableAndDistinct) {
  struct A {};
  struct B {};
  EXPECT_EQ(component_id<A>(), component_id<A>());
  EXPECT_EQ(component_id<const A>(), component_id<A>());
  EXPECT_NE(component_id<A>(), component_id<B>());
  EXPECT_NE(type_name(component_id<A>()).find('A'), std::string_view::npos);
}

}  // namespace
}  // namespace lantern
