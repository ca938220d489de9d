// Bad input: every case gives one lantern::InputError naming the file and the place (JSON
// pointer, line:column, or glTF mesh/accessor/light index).
#include <gtest/gtest.h>

#include <limits>

#include "engine/level/level_loader.h"
#include "tests/level/test_files.h"

namespace lantern {
namespace {

// Writes `text` to a scratch file named `name` and returns the error of loading it.
std::string error_loading(const std::string& name, const std::string& text) {
  const auto file = test::scratch(name);
  test::write_text(file, text);
  return test::input_error_of([&] { load_level(file); });
}

#define EXPECT_HAS(message, part) EXPECT_NE((message).find(part), std::string::npos) << (message)

TEST(BadInput, MalformedJsonNamesLineAndColumn) {
  const std::string e =
      error_loading("syntax.json", "{\n  \"lights\": [\n    { \"type\": \"point\", }\n  ]\n}\n");
  EXPECT_HAS(e, "syntax.json:3:");
  EXPECT_HAS(e, "malformed JSON");
}

TEST(BadInput, MissingLevelFile) {
  const std::string e =
      test::input_error_of([] { load_level_argument("/nonexistent/dir/level.json"); });
  EXPECT_HAS(e, "/nonexistent/dir/level.json");
  EXPECT_HAS(e, "not found");
  const std::string named = test::input_error_of([] { load_level_argument("no_such_level_name"); });
  EXPECT_HAS(named, "no_such_level_name");
  EXPECT_HAS(named, "cornell_lights");  // lists the levels that exist
}

TEST(BadInput, MissingReferencedAsset) {
  const std::string e =
      error_loading("asset.json", R"({"assets": [{"file": "models/gone.gltf"}]})");
  EXPECT_HAS(e, "asset.json");
  EXPECT_HAS(e, "/assets/0/file");
  EXPECT_HAS(e, "gone.gltf");
  const std::string env =
      error_loading("env.json", R"({"environment": {"file": "sky_missing.exr"}})");
  EXPECT_HAS(env, "/environment/file");
}

TEST(BadInput, UnknownKeysSectionsAndTypes) {
  EXPECT_HAS(error_loading("key.json", R"({"primitives": [{"type": "box", "colour": [1, 0, 0]}]})"),
             "/primitives/0/colour: unknown key 'colour'");
  EXPECT_HAS(error_loading("section.json", R"({"lightz": []})"), "/lightz: unknown key");
  EXPECT_HAS(error_loading("prim.json", R"({"primitives": [{"type": "cone"}]})"),
             "/primitives/0/type: unknown primitive type 'cone'");
  EXPECT_HAS(error_loading("light.json", R"({"lights": [{"type": "area", "intensity": 1}]})"),
             "/lights/0/type: unknown light type 'area'");
  EXPECT_HAS(error_loading("beh.json", R"({"behaviours": {"b": {"type": "wobble"}}})"),
             "/behaviours/b/type: unknown behaviour type 'wobble'");
  EXPECT_HAS(error_loading("gen.json", R"({"generators": [{"type": "forest"}]})"),
             "/generators/0/type");
  EXPECT_HAS(
      error_loading("genkey.json", R"({"generators": [{"type": "night_market", "stals": 3}]})"),
      "/generators/0/stals: unknown key");
}

TEST(BadInput, WrongTypes) {
  EXPECT_HAS(
      error_loading(
          "type1.json",
          R"({"lights": [{"type": "point", "position": [0, 0, 0], "intensity": "bright"}]})"),
      "/lights/0/intensity: expected a number, got string");
  EXPECT_HAS(error_loading("type2.json", R"({"camera": {"position": [0, 0]}})"),
             "/camera/position: expected an array of 3 numbers");
  EXPECT_HAS(error_loading("type3.json", R"({"primitives": {"type": "box"}})"),
             "/primitives: expected an array");
  EXPECT_HAS(error_loading("type4.json", R"([1, 2, 3])"), "type4.json: /: expected an object");
}

TEST(BadInput, NonFiniteLightData) {
  // 1e999 overflows a double: JSON cannot say NaN or Inf any other way.
  const std::string e = error_loading(
      "inf.json", R"({"lights": [{"type": "point", "position": [0, 0, 0], "intensity": 1e999}]})");
  EXPECT_HAS(e, "inf.json");
  EXPECT_HAS(e, "inf.json:1:67:");  // line:column of the number
  EXPECT_HAS(e, "1e999");
}

TEST(BadInput, NonFiniteVertexDataInGltf) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const auto doc = test::triangle_gltf({{0, 0, 0}, {1, nan, 0}, {0, 1, 0}}, {0, 1, 2});
  const std::string e = error_loading("nan.gltf", doc.dump());
  EXPECT_HAS(e, "nan.gltf");
  EXPECT_HAS(e, "mesh 0 'tri' primitive 0");
  EXPECT_HAS(e, "accessor 0");
  EXPECT_HAS(e, "position of vertex 1 is not finite");
}

TEST(BadInput, MalformedGltf) {
  EXPECT_HAS(error_loading("broken.gltf",
                           "{ \"asset\": { \"version\": \"2.0\" }, \"nodes\": [ { \"mesh\": 0 } "),
             "broken.gltf: malformed glTF");
  auto doc = test::triangle_gltf({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2});
  doc["buffers"][0]["uri"] = "missing.bin";
  EXPECT_HAS(error_loading("nobin.gltf", doc.dump()), "nobin.gltf: malformed glTF");
}

TEST(BadInput, GltfAccessorOutOfRange) {
  auto doc = test::triangle_gltf({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2});
  doc["accessors"][0]["count"] = 30;  // 30 vertices do not fit 36 bytes
  const std::string e = error_loading("overrun.gltf", doc.dump());
  EXPECT_HAS(e, "overrun.gltf");
  EXPECT_HAS(e, "accessor 0");
  auto bad_index = test::triangle_gltf({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 7});
  EXPECT_HAS(error_loading("index.gltf", bad_index.dump()), "triangle 0 uses vertex 7");
}

TEST(BadInput, GltfLightWithNegativeIntensity) {
  auto doc = test::triangle_gltf({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2});
  doc["extensions"]["KHR_lights_punctual"]["lights"] = {
      {{"type", "point"}, {"intensity", -2.0}, {"name", "neg"}}};
  doc["nodes"].push_back({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  doc["scenes"][0]["nodes"].push_back(1);
  const std::string e = error_loading("neglight.gltf", doc.dump());
  EXPECT_HAS(e, "neglight.gltf: KHR_lights_punctual light 0 'neg' (node 1)");
  EXPECT_HAS(e, "negative");
}

TEST(BadInput, PathWithOneKeyframe) {
  const std::string e = error_loading(
      "path.json", R"({"paths": {"solo": {"keys": [{"time": 0, "position": [0, 0, 0]}]}}})");
  EXPECT_HAS(e, "path.json");
  EXPECT_HAS(e, "/paths/solo");
  EXPECT_HAS(e, "1 keyframe");
  EXPECT_HAS(error_loading("follow.json",
                           R"({"behaviours": {"f": {"type": "follow_path", "path": "nowhere"}}})"),
             "/behaviours/f/path: no path named 'nowhere'");
}

TEST(BadInput, NegativeRadiance) {
  EXPECT_HAS(
      error_loading("neg1.json",
                    R"({"materials": {"m": {"emissive": [1, 1, 1], "emissive_strength": -3}}})"),
      "/materials/m: negative radiance");
  EXPECT_HAS(
      error_loading("neg2.json", R"({"primitives": [{"type": "emissive_quad_grid", "counts": [2, 2],
             "radiance": {"min": -5, "max": 10}}]})"),
      "/primitives/0/radiance/min: negative radiance");
  EXPECT_HAS(
      error_loading("neg3.json",
                    R"({"generators": [{"type": "night_market", "lantern_radiance": [-1, 5]}]})"),
      "/generators/0/lantern_radiance");
}

TEST(BadInput, AbsurdCountsAreCapped) {
  const std::string e = error_loading("huge.json", R"({"primitives": [{"type": "emissive_quad_grid",
      "counts": [1000000, 1000000], "radiance": {"min": 1}}]})");
  EXPECT_HAS(e, "/primitives/0/counts");
  EXPECT_HAS(e, "exceeds the limit");
  EXPECT_HAS(
      error_loading("stalls.json", R"({"generators": [{"type": "night_market", "stalls": 1e12}]})"),
      "/generators/0/stalls: 1000000000000.0 is out of range [1, 20000]");
  EXPECT_HAS(
      error_loading("subdiv.json", R"({"primitives": [{"type": "sphere", "subdivisions": 40}]})"),
      "/primitives/0/subdivisions: 40 is out of range");
}

}  // namespace
}  // namespace lantern
