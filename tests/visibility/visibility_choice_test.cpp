// The visibility setting and the per-device choice (lighting/visibility/visibility_backend.h),
// on hand-made device descriptions: auto is the compute BVH on lavapipe (a CPU device, which
// has ray query) and ray query on GPUs that have it; rayquery without the extension and unknown
// values are one clear InputError.
#include <gtest/gtest.h>

#include <string>

#include "engine/core/error.h"
#include "lighting/visibility/visibility_backend.h"
#include "runtime/core/device_info.h"

namespace lantern::lighting {
namespace {

runtime::DeviceInfo device(const std::string& name, const std::string& type, bool ray_query) {
  runtime::DeviceInfo info;
  info.name = name;
  info.type = type;
  info.ray_query = ray_query;
  return info;
}

const runtime::DeviceInfo kLavapipe = device("llvmpipe (LLVM 15.0.6, 256 bits)", "cpu", true);

TEST(VisibilityChoice, AutoIsTheHostOnLavapipe) {
  const VisibilityChoice c = choose_visibility(kLavapipe, VisibilitySetting::Auto);
  EXPECT_EQ(c.backend, VisibilityBackend::Host);
  EXPECT_NE(c.why.find("cpu"), std::string::npos) << c.why;
  EXPECT_NE(c.why.find("Embree"), std::string::npos) << c.why;
}

TEST(VisibilityChoice, AutoIsRayQueryOnGpusWithHardwareTraversal) {
  for (const char* type : {"discrete", "integrated"}) {
    const VisibilityChoice c = choose_visibility(device("gpu", type, true), VisibilitySetting::Auto);
    EXPECT_EQ(c.backend, VisibilityBackend::RayQuery) << type;
  }
}

TEST(VisibilityChoice, AutoIsTheBvhWithoutRayQueryOrOnVirtualDevices) {
  EXPECT_EQ(choose_visibility(device("old gpu", "discrete", false), VisibilitySetting::Auto).backend,
            VisibilityBackend::Bvh);
  EXPECT_EQ(choose_visibility(device("vm", "virtual", true), VisibilitySetting::Auto).backend,
            VisibilityBackend::Bvh);
}

TEST(VisibilityChoice, ExplicitSettingsWinOverTheDevice) {
  EXPECT_EQ(choose_visibility(kLavapipe, VisibilitySetting::RayQuery).backend,
            VisibilityBackend::RayQuery);
  EXPECT_EQ(choose_visibility(device("gpu", "discrete", true), VisibilitySetting::Bvh).backend,
            VisibilityBackend::Bvh);
  EXPECT_EQ(choose_visibility(kLavapipe, VisibilitySetting::Bvh).backend, VisibilityBackend::Bvh);
  EXPECT_EQ(choose_visibility(device("gpu", "discrete", true), VisibilitySetting::Host).backend,
            VisibilityBackend::Host);
}

TEST(VisibilityChoice, RayQueryOnADeviceWithoutItNamesTheDevice) {
  try {
    (void)choose_visibility(device("Old GPU 9000", "discrete", false), VisibilitySetting::RayQuery);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("Old GPU 9000"), std::string::npos) << what;
    EXPECT_NE(what.find("VK_KHR_ray_query"), std::string::npos) << what;
  }
}

TEST(VisibilityChoice, ParsesTheFourValuesAndRefusesOthers) {
  EXPECT_EQ(parse_visibility_setting("auto"), VisibilitySetting::Auto);
  EXPECT_EQ(parse_visibility_setting("bvh"), VisibilitySetting::Bvh);
  EXPECT_EQ(parse_visibility_setting("rayquery"), VisibilitySetting::RayQuery);
  EXPECT_EQ(parse_visibility_setting("host"), VisibilitySetting::Host);
  for (VisibilitySetting s : {VisibilitySetting::Auto, VisibilitySetting::Bvh,
                              VisibilitySetting::RayQuery, VisibilitySetting::Host})
    EXPECT_EQ(parse_visibility_setting(visibility_setting_name(s)), s);
  EXPECT_THROW((void)parse_visibility_setting("embree"), InputError);
  EXPECT_THROW((void)parse_visibility_setting("RayQuery"), InputError);
  EXPECT_THROW((void)parse_visibility_setting(""), InputError);
}

TEST(VisibilityChoice, VariantsMatchTheCompiledShaders) {
  EXPECT_EQ(visibility_variant(VisibilityBackend::Bvh), "");
  EXPECT_EQ(visibility_variant(VisibilityBackend::RayQuery), "rayquery");
  // The host backend's other passes run the BVH build; its split passes load their own variants.
  EXPECT_EQ(visibility_variant(VisibilityBackend::Host), "");
  EXPECT_EQ(visibility_backend_name(VisibilityBackend::Host), "host");
}

}  // namespace
}  // namespace lantern::lighting
