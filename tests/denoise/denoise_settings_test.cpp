// Denoiser settings: presets, KEY=VALUE parsing, range and key errors, describe round trip.
#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "lighting/denoise/denoise_settings.h"

namespace lantern::lighting {
namespace {

TEST(DenoiseSettings, PresetsDifferInFilterStrength) {
  const DenoiseSettings fast = make_denoise_settings("fast", {});
  const DenoiseSettings quality = make_denoise_settings("quality", {});
  EXPECT_TRUE(fast.enabled);
  EXPECT_LT(fast.atrous_iterations, quality.atrous_iterations);
  EXPECT_GT(fast.color_alpha, quality.color_alpha);
}

TEST(DenoiseSettings, ParsesEveryKindOfKey) {
  const DenoiseSettings s = make_denoise_settings(
      "balanced",
      {{"enabled", "off"}, {"atrous", "2"}, {"phi_luminance", "2.5"}, {"neighbour_clamp", "0"}});
  EXPECT_FALSE(s.enabled);
  EXPECT_EQ(s.neighbour_clamp, 0.0f);
  EXPECT_EQ(make_denoise_settings("balanced", {}).neighbour_clamp, 2.0f);
  EXPECT_FLOAT_EQ(make_denoise_settings("balanced", {}).repay, 0.25f);
  EXPECT_EQ(make_denoise_settings("fast", {{"repay", "0"}}).repay, 0.0f);
  EXPECT_EQ(s.atrous_iterations, 2u);
  EXPECT_FLOAT_EQ(s.phi_luminance, 2.5f);
}

TEST(DenoiseSettings, RefusesBadInputNamingIt) {
  auto message = [](const std::vector<std::pair<std::string, std::string>>& c) -> std::string {
    try {
      (void)make_denoise_settings("balanced", c);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(message({{"strength", "1"}}).find("unknown denoise setting 'strength'"),
            std::string::npos);
  EXPECT_NE(message({{"atrous", "9"}}).find("outside"), std::string::npos);
  EXPECT_NE(message({{"atrous", "1.5"}}).find("whole number"), std::string::npos);
  EXPECT_NE(message({{"firefly", "nan"}}).find("finite"), std::string::npos);
  EXPECT_NE(message({{"neighbour_clamp", "-1"}}).find("'neighbour_clamp': -1 is outside"),
            std::string::npos);
  EXPECT_NE(message({{"repay", "1.5"}}).find("'repay': 1.5 is outside 0..1"), std::string::npos);
  EXPECT_NE(message({{"enabled", "maybe"}}).find("boolean"), std::string::npos);
  EXPECT_THROW((void)make_denoise_settings("ultra", {}), InputError);
}

TEST(DenoiseSettings, DescribeRoundTripsThroughParse) {
  DenoiseSettings s = make_denoise_settings("quality", {{"firefly", "0"}, {"max_history", "7"}});
  const DenoiseSettings back = make_denoise_settings("fast", describe_denoise_settings(s));
  EXPECT_EQ(describe_denoise_settings(back), describe_denoise_settings(s));
  ASSERT_EQ(describe_denoise_settings(s).size(), denoise_keys().size());
}

TEST(DenoiseSettings, PanelValuesClampToTheKeysRange) {
  DenoiseSettings s;
  set_denoise_value(s, "atrous", 100.0f);
  EXPECT_EQ(s.atrous_iterations, gpu::kDenoiseMaxAtrousIterations);
  set_denoise_value(s, "color_alpha", 0.0f);
  EXPECT_FLOAT_EQ(denoise_value(s, "color_alpha"), 0.01f);
}

}  // namespace
}  // namespace lantern::lighting
