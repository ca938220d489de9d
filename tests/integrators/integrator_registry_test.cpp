// The integrator registry without a device: every row is complete, names are unique, an unknown
// name is refused naming it and listing the valid ones, and each row's validate refuses bad
// settings and --spp naming them.
#include "lighting/integrators/integrator_registry.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "engine/core/error.h"

namespace lantern::lighting {
namespace {

std::string error_of(const IntegratorConfig& config) {
  try {
    validate_integrator_config(config);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(IntegratorRegistry, RowsAreCompleteAndNamesUnique) {
  ASSERT_FALSE(integrators().empty());
  std::set<std::string> names;
  for (const IntegratorEntry& entry : integrators()) {
    EXPECT_TRUE(names.insert(entry.name).second) << entry.name << " registered twice";
    EXPECT_GT(std::string(entry.description).size(), 20u) << entry.name;
    EXPECT_NE(entry.validate, nullptr) << entry.name;
    EXPECT_NE(entry.make, nullptr) << entry.name;
    EXPECT_STREQ(find_integrator(entry.name).name, entry.name);
    EXPECT_NE(integrator_names("|").find(entry.name), std::string::npos) << entry.name;
    // Its defaults are valid.
    EXPECT_EQ(error_of({.name = entry.name}), "") << entry.name;
  }
  EXPECT_TRUE(names.count(IntegratorConfig{}.name)) << "the default config names a row";
}

TEST(IntegratorRegistry, UnknownNameIsRefusedListingEveryIntegrator) {
  std::string message;
  try {
    (void)find_integrator("magic");
  } catch (const InputError& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("'magic'"), std::string::npos) << message;
  for (const IntegratorEntry& entry : integrators())
    EXPECT_NE(message.find(entry.name), std::string::npos) << message;
  EXPECT_NE(error_of({.name = "magic"}).find("magic"), std::string::npos);
}

TEST(IntegratorRegistry, EveryRowRefusesAnUnknownSettingNamingIt) {
  for (const IntegratorEntry& entry : integrators()) {
    const std::string message = error_of({.name = entry.name, .settings = {{"no_such_key", "1"}}});
    EXPECT_NE(message.find("no_such_key"), std::string::npos) << entry.name << ": " << message;
  }
}

TEST(IntegratorRegistry, SamplesPerPixelAreTheReferencesAlone) {
  for (const char* one_spp : {"baseline", "restir"}) {
    const std::string message = error_of({.name = one_spp, .spp = 4});
    EXPECT_NE(message.find("--spp 4"), std::string::npos) << one_spp << ": " << message;
    EXPECT_EQ(error_of({.name = one_spp, .spp = 1}), "") << one_spp;
  }
  EXPECT_EQ(error_of({.name = "reference", .spp = 4}), "");
  // `--set reference.spp=N` reaches the reference as "spp" (the CLI strips the prefix).
  EXPECT_EQ(error_of({.name = "reference", .settings = {{"spp", "8"}}}), "");
  EXPECT_EQ(error_of({.name = "reference", .settings = {{"reference.spp", "8"}}}), "");
  EXPECT_NE(error_of({.name = "reference", .settings = {{"spp", "0"}}}).find("spp"),
            std::string::npos);
  // Restir's settings go through its own parser (restir_settings.h), preset included.
  EXPECT_NE(error_of({.name = "restir", .preset = "ultra"}).find("ultra"), std::string::npos);
  EXPECT_NE(error_of({.name = "restir", .settings = {{"light_candidates", "0"}}})
                .find("light_candidates"),
            std::string::npos);
}

}  // namespace
}  // namespace lantern::lighting
