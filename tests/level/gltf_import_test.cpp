// glTF import (tests/level/data/lights_camera.gltf, hand-written): units per CLI.md "glTF units",
// the first camera node, its animation sampled into a path, node transforms, degenerate triangles.
#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>

#include "engine/level/level_loader.h"
#include "engine/scene/level_summary.h"
#include "tests/level/test_files.h"

namespace lantern {
namespace {

void expect_near(glm::vec3 a, glm::vec3 b, float eps = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

class GltfLevel : public ::testing::Test {
 protected:
  void SetUp() override { level = load_level(test::data_dir() / "lights_camera.gltf"); }
  Level level;
};

TEST_F(GltfLevel, EmissiveMaterialIsFactorTimesStrength) {
  ASSERT_EQ(level.instances.size(), 2u);
  const Material& glow = level.materials[level.instances[0].material];
  EXPECT_EQ(glow.name, "glow");
  expect_near(glow.emitted_radiance(), glm::vec3(40.0f, 20.0f, 10.0f));  // W/(sr·m²)
  EXPECT_FLOAT_EQ(glow.specular_factor, 0.0f);                           // KHR_materials_specular
  EXPECT_FLOAT_EQ(glow.metallic, 0.0f);
  EXPECT_FLOAT_EQ(glow.roughness, 0.9f);
  const Material& grey = level.materials[level.instances[1].material];
  EXPECT_FALSE(grey.emissive());
  EXPECT_FLOAT_EQ(grey.specular_factor, 1.0f);  // default: dielectric specular layer on
  const LevelSummary s = summarize(level);
  EXPECT_EQ(s.triangles, 3u);
  EXPECT_EQ(s.emissive_triangles, 2u);
}

TEST_F(GltfLevel, MeshesCarryNodeTransformsAndComputedNormals) {
  const Instance& panel = level.instances[0];
  expect_near(panel.transform.translation, glm::vec3(0, 0, -2));
  const Mesh& quad = level.meshes[panel.mesh];
  EXPECT_EQ(quad.triangle_count(), 2u);
  for (const glm::vec3& n : quad.normals)
    expect_near(n, glm::vec3(0, 0, 1));  // computed: CCW front
  expect_near(quad.bounds.min, glm::vec3(-1, -1, 0));
  expect_near(quad.bounds.max, glm::vec3(1, 1, 0));
  expect_near(level.instances[1].transform.scale, glm::vec3(2));
}

TEST_F(GltfLevel, PunctualLightsAreRadiometric) {
  ASSERT_EQ(level.lights.size(), 3u);
  const Light& point = level.lights[0];
  EXPECT_EQ(point.type, LightType::Point);
  EXPECT_FLOAT_EQ(point.intensity, 5.0f);  // W/sr, no 683 lm/W conversion
  expect_near(point.color, glm::vec3(1.0f, 0.5f, 0.25f));
  expect_near(point.position, glm::vec3(1, 2, 3));
  EXPECT_FLOAT_EQ(point.range, 0.0f);  // no range: inverse square
  const Light& spot = level.lights[1];
  EXPECT_EQ(spot.type, LightType::Spot);
  EXPECT_FLOAT_EQ(spot.intensity, 10.0f);
  EXPECT_FLOAT_EQ(spot.inner_cone, 0.2f);
  EXPECT_FLOAT_EQ(spot.outer_cone, 0.6f);
  expect_near(spot.direction(), glm::vec3(0, -1, 0));  // node rotated -90° about X
  const Light& sun = level.lights[2];
  EXPECT_EQ(sun.type, LightType::Directional);
  EXPECT_FLOAT_EQ(sun.intensity, 3.0f);  // W/m²
  expect_near(sun.direction(), glm::vec3(0, 0, -1));
}

TEST_F(GltfLevel, FirstCameraNodeIsTheCamera) {
  EXPECT_TRUE(level.has_camera);
  EXPECT_FLOAT_EQ(level.camera.yfov, 0.7f);
  EXPECT_FLOAT_EQ(level.camera.aspect, 1.5f);
  EXPECT_FLOAT_EQ(level.camera.znear, 0.1f);
  EXPECT_FLOAT_EQ(level.camera.zfar, 100.0f);
  expect_near(level.camera.position, glm::vec3(0, 1, 5));    // node "cam", not "cam2"
  expect_near(level.camera.forward(), glm::vec3(0, 0, -1));  // looks down local -Z
}

TEST_F(GltfLevel, CameraAnimationBecomesThePath) {
  ASSERT_EQ(level.paths.size(), 1u);
  EXPECT_EQ(level.camera_path, "fly");
  const CameraPath& path = level.paths[0];
  ASSERT_EQ(path.keys.size(),
            3u);  // union of the translation (0, 1, 2) and rotation (0, 2) key times
  EXPECT_FLOAT_EQ(path.keys[1].time, 1.0f);
  expect_near(path.keys[0].position, glm::vec3(0, 1, 5));
  expect_near(path.keys[1].position, glm::vec3(1, 1, 4));
  expect_near(path.keys[2].position, glm::vec3(2, 1, 3));
  // Rotation 0° -> 30° about +Y over 2 s: 15° at t = 1 (slerp of the channel).
  const glm::vec3 f1 = path.keys[1].orientation * glm::vec3(0, 0, -1);
  expect_near(f1, glm::vec3(-std::sin(glm::radians(15.0f)), 0, -std::cos(glm::radians(15.0f))));
  const PathPose end = path.evaluate(5.0f);  // clamped
  expect_near(end.position, glm::vec3(2, 1, 3));
}

TEST(GltfDegenerate, ZeroAreaTrianglesAreSkippedWithOneCountingWarning) {
  // Triangle 0 is fine, 1 repeats a vertex, 2 is collinear, 3 is fine.
  const std::vector<glm::vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {1, 1, 0}};
  const std::vector<std::uint32_t> idx = {0, 1, 2, 0, 0, 1, 0, 1, 3, 1, 4, 2};
  const auto file = test::scratch("degenerate.gltf");
  test::write_text(file, test::triangle_gltf(p, idx).dump());
  ::testing::internal::CaptureStderr();
  const Level level = load_level(file);
  const std::string log = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(level.meshes[0].triangle_count(), 2u);
  EXPECT_NE(log.find("skipped 2 degenerate (zero-area) triangles"), std::string::npos) << log;
  EXPECT_NE(log.find("degenerate.gltf"), std::string::npos) << log;
  std::size_t warnings = 0;
  for (std::size_t at = log.find("warning:"); at != std::string::npos;
       at = log.find("warning:", at + 1))
    ++warnings;
  EXPECT_EQ(warnings, 1u) << log;
}

TEST(GltfBinary, GlbLoadsLikeGltf) {
  const std::vector<glm::vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<std::uint32_t> idx = {0, 1, 2};
  nlohmann::json doc = test::triangle_gltf(p, idx);
  doc["buffers"][0].erase("uri");
  const auto file = test::scratch("triangle.glb");
  test::write_glb(file, doc, test::triangle_buffer(p, idx));
  const Level level = load_level(file);
  ASSERT_EQ(level.meshes.size(), 1u);
  EXPECT_EQ(level.meshes[0].positions, p);
  EXPECT_EQ(level.meshes[0].indices, idx);
  EXPECT_FALSE(level.has_camera);  // framed automatically: it sees the triangle
  EXPECT_GT(glm::dot(level.camera.forward(), glm::vec3(0.5f, 0.5f, 0.0f) - level.camera.position),
            0.0f);
}

TEST(GltfImages, TexturesReferenceEmbeddedBytesOrFiles) {
  nlohmann::json doc = test::triangle_gltf({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2});
  doc["images"] = {{{"uri", "data:image/png;base64,UE5HREFUQQ=="}},
                   {{"uri", "albedo.png"}, {"name", "albedo"}}};
  doc["textures"] = {{{"source", 0}}, {{"source", 1}}};
  doc["materials"][0]["emissiveTexture"] = {{"index", 0}};
  doc["materials"][0]["pbrMetallicRoughness"] = {
      {"baseColorTexture", {{"index", 1}, {"texCoord", 0}}}};
  // Textured materials need the texcoord set they sample (the positions' bytes read as VEC2).
  doc["accessors"].push_back(
      {{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}});
  doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 2;
  const auto file = test::scratch("textured.gltf");
  test::write_text(file, doc.dump());
  test::write_text(test::scratch("albedo.png"), "not decoded at load time");
  const Level level = load_level(file);
  ASSERT_EQ(level.images.size(), 2u);
  const Material& m = level.materials[level.instances[0].material];
  const ImageRef& embedded = level.images[static_cast<std::size_t>(m.emissive_texture.image)];
  EXPECT_EQ(std::string(embedded.embedded.begin(), embedded.embedded.end()), "PNGDATA");
  EXPECT_TRUE(embedded.path.empty());
  const ImageRef& external = level.images[static_cast<std::size_t>(m.base_color_texture.image)];
  EXPECT_EQ(external.path.filename(), "albedo.png");
  EXPECT_TRUE(external.embedded.empty());

  doc["images"][1]["uri"] = "missing.png";
  test::write_text(file, doc.dump());
  const std::string e = test::input_error_of([&] { load_level(file); });
  EXPECT_NE(e.find("textured.gltf: image 1"), std::string::npos) << e;
  EXPECT_NE(e.find("missing.png"), std::string::npos) << e;
}

}  // namespace
}  // namespace lantern
