// Singleton resources: one value per type, replaceable, a missing one is a named error.
#include <gtest/gtest.h>

#include <memory>

#include "engine/ecs/registry.h"

namespace lantern {
namespace {

struct Settings {
  int spp = 1;
  float exposure = 1.0f;
};
struct Counter {
  std::shared_ptr<int> alive;
};

TEST(Resources, EmplaceGetReplaceErase) {
  Registry r;
  EXPECT_FALSE(r.ctx().contains<Settings>());
  EXPECT_EQ(r.ctx().find<Settings>(), nullptr);
  r.ctx().emplace<Settings>(4, 2.0f);
  EXPECT_EQ(r.ctx().get<Settings>().spp, 4);
  r.ctx().get<Settings>().spp = 8;
  EXPECT_EQ(std::as_const(r).ctx().get<Settings>().spp, 8);
  r.ctx().emplace<Settings>(16, 1.0f);  // replaces
  EXPECT_EQ(r.ctx().get<Settings>().spp, 16);
  EXPECT_TRUE(r.ctx().erase<Settings>());
  EXPECT_FALSE(r.ctx().erase<Settings>());
  EXPECT_FALSE(r.ctx().contains<Settings>());
}

TEST(Resources, MissingResourceIsANamedError) {
  Registry r;
  try {
    r.ctx().get<Settings>();
    FAIL() << "expected an error";
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("Settings"), std::string::npos) << e.what();
  }
}

TEST(Resources, DestroyedWithTheRegistry) {
  auto token = std::make_shared<int>(0);
  {
    Registry r;
    r.ctx().emplace<Counter>(token);
    EXPECT_EQ(token.use_count(), 2);
  }
  EXPECT_EQ(token.use_count(), 1);
}

}  // namespace
}  // namespace lantern
