// Construct/update/destroy signals fire at the right moment, in order, with the right entity.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "engine/ecs/registry.h"

namespace lantern {
namespace {

struct Mass {
  float kg = 0;
};
struct Name {
  std::string text;
};

struct Event {
  std::string what;
  Entity entity;
  float value;  // Mass at the time of the event (or -1 when absent)
  bool operator==(const Event&) const = default;
};

TEST(Signals, FireInOrderWithEntityAndValue) {
  Registry r;
  std::vector<Event> log;
  const auto mass_of = [](Registry& reg, Entity e) {
    const Mass* m = reg.try_get<Mass>(e);
    return m ? m->kg : -1.0f;
  };
  r.on_construct<Mass>().connect([&](Registry& reg, Entity e) { log.push_back({"construct", e, mass_of(reg, e)}); });
  r.on_update<Mass>().connect([&](Registry& reg, Entity e) { log.push_back({"update", e, mass_of(reg, e)}); });
  r.on_destroy<Mass>().connect([&](Registry& reg, Entity e) { log.push_back({"destroy", e, mass_of(reg, e)}); });

  const Entity a = r.create();
  const Entity b = r.create();
  r.emplace<Mass>(a, 1.0f);
  r.emplace<Mass>(b, 2.0f);
  r.patch<Mass>(a, [](Mass& m) { m.kg = 3.0f; });
  r.replace<Mass>(b, Mass{4.0f});
  r.get<Mass>(a).kg = 5.0f;  // plain writes do not signal
  r.remove<Mass>(b);
  r.destroy(a);

  const std::vector<Event> expected{
      {"construct", a, 1.0f}, {"construct", b, 2.0f}, {"update", a, 3.0f},
      {"update", b, 4.0f},    {"destroy", b, 4.0f},   {"destroy", a, 5.0f},
  };
  EXPECT_EQ(log, expected);
}

TEST(Signals, ListenersRunInConnectionOrderAndCanDisconnect) {
  Registry r;
  std::string order;
  r.on_construct<Name>().connect([&](Registry&, Entity) { order += "1"; });
  const auto second = r.on_construct<Name>().connect([&](Registry&, Entity) { order += "2"; });
  r.on_construct<Name>().connect([&](Registry&, Entity) { order += "3"; });
  r.emplace<Name>(r.create(), "x");
  r.on_construct<Name>().disconnect(second);
  r.emplace<Name>(r.create(), "y");
  EXPECT_EQ(order, "12313");
}

TEST(Signals, DestroyFiresForEveryComponentBeforeInvalidation) {
  Registry r;
  int fired = 0;
  r.on_destroy<Name>().connect([&](Registry& reg, Entity e) {
    EXPECT_TRUE(reg.valid(e));
    EXPECT_EQ(reg.get<Name>(e).text, "gone");
    ++fired;
  });
  r.on_destroy<Mass>().connect([&](Registry& reg, Entity e) {
    EXPECT_TRUE(reg.valid(e));
    ++fired;
  });
  const Entity e = r.create();
  r.emplace<Name>(e, "gone");
  r.emplace<Mass>(e, 1.0f);
  r.destroy(e);
  EXPECT_EQ(fired, 2);
}

}  // namespace
}  // namespace lantern
