// RestirSettings: presets, every key settable, bad keys and values rejected with InputError
// naming the key and value; the presampling tiles a frame gets; what reaches the push constants
// in raw and denoised frames (temporal permutation, the cap where points move) and that cap's
// closed form (shared/restir.h).
#include "lighting/restir/restir_settings.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "lighting/frame/frame_inputs.h"
#include "lighting/restir/restir_integrator.h"

namespace lantern::lighting {
namespace {

std::string error_of(std::string_view key, std::string_view value) {
  RestirSettings s;
  try {
    apply_setting(s, key, value);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(RestirSettings, PresetsDiffer) {
  const RestirSettings fast = restir_preset("fast");
  const RestirSettings balanced = restir_preset("balanced");
  const RestirSettings quality = restir_preset("quality");
  EXPECT_LT(fast.light_candidates, balanced.light_candidates);
  EXPECT_LT(balanced.light_candidates, quality.light_candidates);
  EXPECT_EQ(fast.bias_correction, gpu::kBiasCorrectionNone);
  EXPECT_EQ(balanced.bias_correction, gpu::kBiasCorrectionPairwise);
  EXPECT_EQ(quality.bias_correction, gpu::kBiasCorrectionBalance);
  EXPECT_THROW(restir_preset("ultra"), InputError);
  EXPECT_EQ(balanced.m_cap(), 20.0f * balanced.candidates()) << "default M cap: 20x current M";
}

TEST(RestirSettings, EveryDescribedKeyRoundTrips) {
  // Applying each key's own described value to the defaults changes nothing: every key parses.
  const RestirSettings q = restir_preset("quality");
  for (const auto& [key, value] : describe(q)) {
    RestirSettings s = restir_preset("fast");
    EXPECT_NO_THROW(apply_setting(s, key, value)) << key << "=" << value;
  }
  RestirSettings s = make_restir_settings("fast", describe(q));
  EXPECT_EQ(describe(s), describe(q));
}

TEST(RestirSettings, AppliesValues) {
  RestirSettings s = make_restir_settings(
      "balanced", {{"light_candidates", "32"}, {"temporal", "off"}, {"bias_correction", "balance"},
                   {"radius", "8.5"}, {"debug_view", "disocclusion"}, {"m_cap", "5"}});
  EXPECT_EQ(s.light_candidates, 32u);
  EXPECT_FALSE(s.temporal);
  EXPECT_EQ(s.bias_correction, gpu::kBiasCorrectionBalance);
  EXPECT_FLOAT_EQ(s.radius, 8.5f);
  EXPECT_EQ(s.debug_view, gpu::kRestirDebugDisocclusion);
  EXPECT_FLOAT_EQ(s.m_cap(), 5.0f * 32.0f);
}

// The media reservoirs' knobs: their own keys, presets and cap (RestirSettings::Volume).
TEST(RestirSettings, VolumeKnobsApplyAndScaleWithThePresets) {
  RestirSettings s = make_restir_settings(
      "balanced", {{"volume_candidates", "12"}, {"volume_temporal", "off"},
                   {"volume_m_cap", "5"}, {"volume_neighbours", "0"}, {"volume_radius", "20"}});
  EXPECT_EQ(s.volume.candidates, 12u);
  EXPECT_FALSE(s.volume.temporal);
  EXPECT_FLOAT_EQ(s.volume.m_cap(), 5.0f * 12.0f);
  EXPECT_EQ(s.volume.neighbours, 0u);
  EXPECT_FLOAT_EQ(s.volume.radius, 20.0f);
  EXPECT_LT(restir_preset("fast").volume.candidates, restir_preset("balanced").volume.candidates);
  EXPECT_LT(restir_preset("balanced").volume.candidates,
            restir_preset("quality").volume.candidates);
  EXPECT_LE(restir_preset("quality").volume.neighbours, gpu::kVolumeRestirMaxNeighbours);
}

TEST(RestirSettings, RejectsBadKeysAndValuesNamingThem) {
  EXPECT_NE(error_of("light_candidate", "8").find("light_candidate"), std::string::npos);
  EXPECT_NE(error_of("light_candidate", "8").find("light_candidates"), std::string::npos)
      << "the message lists the valid keys";
  for (auto [key, value] : std::vector<std::pair<std::string, std::string>>{
           {"light_candidates", "0"},
           {"light_candidates", "1000000000"},
           {"light_candidates", "-3"},
           {"light_candidates", "8x"},
           {"light_candidates", ""},
           {"bsdf_candidates", "17"},
           {"bsdf_min_gloss", "-0.1"},
           {"bsdf_min_gloss", "1.5"},
           {"bsdf_min_gloss", "nan"},
           {"spatial_passes", "5"},
           {"neighbours", "9"},
           {"temporal_neighbours", "9"},
           {"temporal_neighbours", "-1"},
           {"temporal_neighbours", "two"},
           {"reservoir_stride", "0"},
           {"reservoir_stride", "5"},
           {"radius", "0"},
           {"radius", "nan"},
           {"radius", "inf"},
           {"m_cap", "0.5"},
           {"m_cap_moving", "0"},
           {"m_cap_moving", "1.5"},
           {"m_cap_moving", "nan"},
           {"boiling_filter", "1.5"},
           {"bias_correction", "unbiased"},
           {"temporal", "maybe"},
           {"debug_view", "normals"},
           {"volume_candidates", "0"},
           {"volume_candidates", "65"},
           {"volume_neighbours", "7"},
           {"volume_radius", "0"},
           {"volume_m_cap", "nan"},
           {"volume_temporal", "sometimes"},
           {"local_candidates", "257"},
           {"local_candidates", "-1"},
           {"local_min_lights", "0"},
           {"light_spread", "-1"},
           {"light_spread", "nan"},
           {"light_spread", "automatic"},
       }) {
    const std::string message = error_of(key, value);
    EXPECT_NE(message.find(key), std::string::npos) << key << "=" << value << ": " << message;
    if (!value.empty()) {
      EXPECT_NE(message.find(value), std::string::npos) << key << "=" << value << ": " << message;
    }
  }
}

// The bias-correction and debug-view tables name the shared constants the shaders test: every
// constant once, each name parsing to its constant and described back, each with its sentence.
TEST(RestirSettings, ChoiceTablesNameEverySharedConstantOnce) {
  struct Table {
    const char* key;
    std::span<const RestirChoice> rows;
    std::set<std::uint32_t> constants;
  };
  const Table tables[] = {
      {"bias_correction",
       restir_bias_corrections(),
       {gpu::kBiasCorrectionNone, gpu::kBiasCorrectionBalance, gpu::kBiasCorrectionPairwise}},
      {"debug_view",
       restir_debug_views(),
       {gpu::kRestirDebugNone, gpu::kRestirDebugW, gpu::kRestirDebugM, gpu::kRestirDebugAge,
        gpu::kRestirDebugLight, gpu::kRestirDebugDisocclusion, gpu::kRestirDebugMotion}},
      {"temporal_permutation",
       restir_temporal_permutations(),
       {kTemporalPermutationOff, kTemporalPermutationOn, kTemporalPermutationDenoised}},
  };
  EXPECT_EQ(tables[1].constants.size(), gpu::kRestirDebugCount);
  for (const Table& t : tables) {
    std::set<std::uint32_t> named;
    for (const RestirChoice& row : t.rows) {
      EXPECT_TRUE(named.insert(row.value).second) << t.key << ": " << row.value << " named twice";
      EXPECT_GT(std::string_view(row.when).size(), 20u) << t.key << "=" << row.name;
      RestirSettings s;
      apply_setting(s, t.key, row.name);
      const std::string_view table = t.key;
      EXPECT_EQ(table == "debug_view"             ? s.debug_view
                : table == "temporal_permutation" ? s.temporal_permutation
                                                  : s.bias_correction,
                row.value)
          << t.key << "=" << row.name;
      bool described = false;
      for (const auto& [key, value] : describe(s)) described |= key == t.key && value == row.name;
      EXPECT_TRUE(described) << t.key << "=" << row.name;
    }
    EXPECT_EQ(named, t.constants) << t.key;
  }
  EXPECT_NE(error_of("debug_view", "normals").find("disocclusion"), std::string::npos)
      << "the message lists the valid views";
}

}  // namespace
}  // namespace lantern::lighting

namespace lantern::lighting {
namespace {

FrameInputs inputs_of(std::uint32_t width, std::uint32_t height, std::uint32_t lights) {
  FrameInputs in;
  in.width = width;
  in.height = height;
  in.light_count = lights;
  return in;
}

// Presampling: off when the lights fit in one tile; the setting where the candidate draws are
// many; fewer tiles where the presampled entries would exceed 1/8 of the draws; at least one.
TEST(RestirSettings, PresampleTilesFollowLightsAndResolution) {
  const RestirSettings s = restir_preset("balanced");  // 8 candidates, 32 tiles
  ASSERT_EQ(s.presample_tiles, 32u);
  EXPECT_EQ(RestirIntegrator::presample_tiles(s, inputs_of(320, 180, 1024)), 0u);
  EXPECT_EQ(RestirIntegrator::presample_tiles(s, inputs_of(320, 180, 123000)), 32u);
  // 160x90 x 8 = 115200 draws: 14 tiles of 1024 stay within 1/8 of them.
  EXPECT_EQ(RestirIntegrator::presample_tiles(s, inputs_of(160, 90, 123000)), 14u);
  EXPECT_EQ(RestirIntegrator::presample_tiles(s, inputs_of(8, 8, 123000)), 1u);
  RestirSettings off = s;
  apply_setting(off, "presample_tiles", "0");
  EXPECT_EQ(RestirIntegrator::presample_tiles(off, inputs_of(320, 180, 123000)), 0u);
  EXPECT_EQ(RestirIntegrator::make_push(s, inputs_of(320, 180, 123000)).presample_tiles, 32u);
}

// Local light lists: the setting where the level has more lights than one presampling tile
// (night_market), none where RIS over the power distribution finds every light (cornell_lights),
// or from local_min_lights lights; more draws per slot in the richer presets; 0 turns them off.
TEST(RestirSettings, LocalListsFollowTheLightCount) {
  const RestirSettings s = restir_preset("balanced");
  ASSERT_GT(s.local_candidates, 0u);
  EXPECT_LT(restir_preset("fast").local_candidates, s.local_candidates);
  EXPECT_LT(s.local_candidates, restir_preset("quality").local_candidates);
  EXPECT_EQ(RestirIntegrator::local_candidates(s, inputs_of(320, 180, 1024)), 0u);
  EXPECT_EQ(RestirIntegrator::local_candidates(s, inputs_of(320, 180, 1025)), s.local_candidates);
  EXPECT_EQ(RestirIntegrator::make_push(s, inputs_of(320, 180, 123000)).local_candidates,
            s.local_candidates);
  EXPECT_EQ(RestirIntegrator::make_push(s, inputs_of(320, 180, 89)).local_candidates, 0u);
  RestirSettings off = s;
  apply_setting(off, "local_candidates", "0");
  EXPECT_EQ(RestirIntegrator::make_push(off, inputs_of(320, 180, 123000)).local_candidates, 0u);
  apply_setting(off, "local_candidates", std::to_string(gpu::kRestirMaxLocalCandidates));
  EXPECT_EQ(off.local_candidates, gpu::kRestirMaxLocalCandidates);
  RestirSettings few = s;
  apply_setting(few, "local_min_lights", "64");
  EXPECT_EQ(RestirIntegrator::local_candidates(few, inputs_of(320, 180, 89)), s.local_candidates);
  EXPECT_EQ(RestirIntegrator::local_candidates(few, inputs_of(320, 180, 63)), 0u);
}

// Light grid candidates: drawn where the local lists are (the same light count and spread rule),
// more in the richer presets, counted among the candidates a frame draws (the M cap, the short
// history); 0 turns them off.
TEST(RestirSettings, GridCandidatesFollowTheLocalLists) {
  const RestirSettings s = restir_preset("balanced");
  ASSERT_GT(s.grid_candidates, 0u);
  EXPECT_LT(restir_preset("fast").grid_candidates, s.grid_candidates);
  EXPECT_LT(s.grid_candidates, restir_preset("quality").grid_candidates);
  const FrameInputs many = inputs_of(320, 180, 123000);
  const gpu::RestirPush on = RestirIntegrator::make_push(s, many);
  EXPECT_EQ(on.grid_candidates, s.grid_candidates);
  EXPECT_EQ(on.short_history_m, 2 * (s.light_candidates + s.grid_candidates));
  EXPECT_EQ(RestirIntegrator::make_push(s, inputs_of(320, 180, 89)).grid_candidates, 0u);
  FrameInputs alike = many;
  alike.light_spread = 4.1f;
  EXPECT_EQ(RestirIntegrator::grid_candidates(s, alike), 0u);
  RestirSettings off = s;
  apply_setting(off, "grid_candidates", "0");
  const gpu::RestirPush none = RestirIntegrator::make_push(off, many);
  EXPECT_EQ(none.grid_candidates, 0u);
  EXPECT_EQ(none.short_history_m, 2 * s.light_candidates);
  EXPECT_THROW(apply_setting(off, "grid_candidates", "257"), InputError);
  EXPECT_THROW(apply_setting(off, "grid_candidates", "-1"), InputError);
}

// The light spread (SceneData::light_spread): a level whose lights reach its surfaces alike
// (light_panels, 4.1) gets no local lists and as many presampling tiles as its spread rounded up;
// one whose lights each light their surroundings (night_market, 60) gets both as before, and so
// does a frame whose spread nobody measured. `light_spread` states one instead; `auto` goes back.
TEST(RestirSettings, LightSpreadSetsTilesAndLocalLists) {
  const RestirSettings s = restir_preset("balanced");  // 32 tiles
  FrameInputs alike = inputs_of(320, 180, 1000000);
  alike.light_spread = 4.1f;
  FrameInputs local = alike;
  local.light_spread = 60.0f;
  const FrameInputs unmeasured = inputs_of(320, 180, 1000000);
  EXPECT_EQ(RestirIntegrator::presample_tiles(s, alike), 5u);
  EXPECT_EQ(RestirIntegrator::local_candidates(s, alike), 0u);
  EXPECT_EQ(RestirIntegrator::presample_tiles(s, local), 32u);
  EXPECT_EQ(RestirIntegrator::local_candidates(s, local), s.local_candidates);
  EXPECT_EQ(RestirIntegrator::presample_tiles(s, unmeasured), 32u);
  EXPECT_EQ(RestirIntegrator::local_candidates(s, unmeasured), s.local_candidates);
  // At the threshold the lists are on; the fewest tiles is 1, and resolution still caps them.
  FrameInputs edge = alike;
  edge.light_spread = RestirIntegrator::kLocalListsMinSpread;
  EXPECT_EQ(RestirIntegrator::local_candidates(s, edge), s.local_candidates);
  EXPECT_EQ(RestirIntegrator::presample_tiles(s, edge), 16u);
  edge.light_spread = 0.0f;
  EXPECT_EQ(RestirIntegrator::presample_tiles(s, edge), 1u);
  edge.light_spread = 60.0f;
  edge.width = 160;
  edge.height = 90;
  EXPECT_EQ(RestirIntegrator::presample_tiles(s, edge), 14u);

  RestirSettings stated = s;
  apply_setting(stated, "light_spread", "1000");
  EXPECT_EQ(RestirIntegrator::presample_tiles(stated, alike), 32u);
  EXPECT_EQ(RestirIntegrator::local_candidates(stated, alike), s.local_candidates);
  apply_setting(stated, "light_spread", "2.5");
  EXPECT_EQ(RestirIntegrator::presample_tiles(stated, local), 3u);
  EXPECT_EQ(RestirIntegrator::local_candidates(stated, local), 0u);
  EXPECT_EQ(RestirIntegrator::make_push(stated, local).presample_tiles, 3u);
  apply_setting(stated, "light_spread", "auto");
  EXPECT_EQ(RestirIntegrator::presample_tiles(stated, alike), 5u);
  EXPECT_EQ(describe(stated), describe(s));
}

// Temporal permutation: `denoised` (the default, every preset) sets the shaders' flag exactly
// for frames the denoiser consumes; `on` and `off` whatever the output.
TEST(RestirSettings, TemporalPermutationFollowsTheDenoiser) {
  FrameInputs raw = inputs_of(320, 180, 89);
  FrameInputs denoised = raw;
  denoised.denoised = true;
  auto permuted = [](const RestirSettings& s, const FrameInputs& in) {
    return (RestirIntegrator::make_push(s, in).flags & gpu::kRestirFlagTemporalPermutation) != 0u;
  };
  for (const std::string& preset : restir_preset_names()) {
    const RestirSettings s = restir_preset(preset);
    EXPECT_EQ(s.temporal_permutation, kTemporalPermutationDenoised) << preset;
    EXPECT_FALSE(permuted(s, raw)) << preset;
    EXPECT_TRUE(permuted(s, denoised)) << preset;
  }
  RestirSettings s = restir_preset("balanced");
  apply_setting(s, "temporal_permutation", "on");
  EXPECT_TRUE(permuted(s, raw));
  EXPECT_TRUE(permuted(s, denoised));
  apply_setting(s, "temporal_permutation", "off");
  EXPECT_FALSE(permuted(s, raw));
  EXPECT_FALSE(permuted(s, denoised));
  EXPECT_THROW(apply_setting(s, "temporal_permutation", "sometimes"), InputError);
}

// The lower cap where points move reaches the shaders only in frames the denoiser consumes: raw
// frames (EXR, bias studies) keep the full cap everywhere (m_cap_moving 1).
TEST(RestirSettings, MovingPointsCapFollowsTheDenoiser) {
  FrameInputs raw = inputs_of(320, 180, 89);
  FrameInputs denoised = raw;
  denoised.denoised = true;
  for (const std::string& preset : restir_preset_names()) {
    const RestirSettings s = restir_preset(preset);
    EXPECT_FLOAT_EQ(s.m_cap_moving, 0.25f) << preset;
    EXPECT_FLOAT_EQ(RestirIntegrator::make_push(s, raw).m_cap_moving, 1.0f) << preset;
    EXPECT_FLOAT_EQ(RestirIntegrator::make_push(s, denoised).m_cap_moving, 0.25f) << preset;
    EXPECT_FLOAT_EQ(RestirIntegrator::make_push(s, denoised).m_cap, s.m_cap()) << preset;
  }
  RestirSettings s = restir_preset("balanced");
  apply_setting(s, "m_cap_moving", "1");
  EXPECT_FLOAT_EQ(RestirIntegrator::make_push(s, denoised).m_cap_moving, 1.0f);
  apply_setting(s, "m_cap_moving", "0.5");
  EXPECT_FLOAT_EQ(RestirIntegrator::make_push(s, denoised).m_cap_moving, 0.5f);
}

// restir.temporal's cap (shared/restir.h): the full cap on a still point, the fraction from one
// pixel of own motion on, linear between; a point whose motion is unknown counts as moving.
TEST(RestirHistoryCap, FullWhereStillLowerWhereMoving) {
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FLOAT_EQ(gpu::restir_history_m_cap(160.0f, 0.25f, glm::vec2(0.0f)), 160.0f);
  EXPECT_FLOAT_EQ(gpu::restir_history_m_cap(160.0f, 0.25f, glm::vec2(0.6f, 0.8f)), 40.0f);
  EXPECT_FLOAT_EQ(gpu::restir_history_m_cap(160.0f, 0.25f, glm::vec2(-30.0f, 4.0f)), 40.0f);
  EXPECT_FLOAT_EQ(gpu::restir_history_m_cap(160.0f, 0.25f, glm::vec2(0.0f, 0.5f)), 100.0f);
  EXPECT_FLOAT_EQ(gpu::restir_history_m_cap(160.0f, 0.25f, glm::vec2(inf, 0.0f)), 40.0f);
  EXPECT_FLOAT_EQ(gpu::restir_history_m_cap(160.0f, 0.25f, glm::vec2(0.0f, nan)), 40.0f);
  // 1: the same cap everywhere (raw frames).
  EXPECT_FLOAT_EQ(gpu::restir_history_m_cap(160.0f, 1.0f, glm::vec2(5.0f, 0.0f)), 160.0f);
  EXPECT_FLOAT_EQ(gpu::restir_history_m_cap(160.0f, 1.0f, glm::vec2(nan)), 160.0f);
}

// BSDF candidates reach the shaders with the gloss they need, and not at all on a level none of
// whose materials reaches it (FrameInputs::max_gloss): its frame then runs no BSDF ray pass.
TEST(RestirSettings, BsdfCandidatesOnlyWhereALevelHasGlossySurfaces) {
  FrameInputs inputs = inputs_of(320, 180, 89);
  RestirSettings s = restir_preset("balanced");
  EXPECT_EQ(s.bsdf_min_gloss, 0.0f) << "by default every surface draws them";
  apply_setting(s, "bsdf_candidates", "2");
  inputs.max_gloss = 0.0f;
  EXPECT_EQ(RestirIntegrator::make_push(s, inputs).bsdf_candidates, 2u) << "0 gates nothing";
  apply_setting(s, "bsdf_min_gloss", "0.5");
  for (auto [max_gloss, expected] : {std::pair{1.0f, 2u}, {0.5f, 2u}, {0.49f, 0u}, {0.0f, 0u}}) {
    inputs.max_gloss = max_gloss;
    const gpu::RestirPush push = RestirIntegrator::make_push(s, inputs);
    EXPECT_EQ(push.bsdf_candidates, expected) << "level's glossiest surface " << max_gloss;
    EXPECT_FLOAT_EQ(push.bsdf_min_gloss, 0.5f);
    // The history cap and the short-history threshold count the candidates the frame draws.
    EXPECT_FLOAT_EQ(push.m_cap, s.m_cap_factor * static_cast<float>(8u + expected));
    EXPECT_EQ(push.short_history_m, 2u * (8u + expected));
  }
  EXPECT_EQ(restir_preset("quality").bsdf_min_gloss, 0.0f) << "quality: every surface";
}

// restir.temporal's neighbours from last frame reach the shaders as set, the spelling
// "neighbors" too; every preset leaves them off (their measured trade: README).
TEST(RestirSettings, TemporalNeighboursReachTheTemporalPass) {
  const FrameInputs inputs = inputs_of(320, 180, 89);
  for (const std::string& preset : restir_preset_names()) {
    EXPECT_EQ(restir_preset(preset).temporal_neighbours, 0u) << preset;
    EXPECT_EQ(RestirIntegrator::make_push(restir_preset(preset), inputs).temporal_neighbours, 0u);
  }
  RestirSettings s = make_restir_settings("balanced", {{"temporal_neighbours", "4"}});
  EXPECT_EQ(RestirIntegrator::make_push(s, inputs).temporal_neighbours, 4u);
  apply_setting(s, "temporal_neighbors", "8");
  EXPECT_EQ(RestirIntegrator::make_push(s, inputs).temporal_neighbours, gpu::kRestirMaxNeighbours);
}

// One reservoir per stride x stride pixels: off (1) in every preset; the stride reaches the
// shaders, and each cell's representative pixel visits every offset of its block once in
// stride^2 frames; visibility reuse (one pixel's verdict) is refused beside it.
TEST(RestirSettings, ReservoirStrideReachesThePassesAndVisitsEveryPixel) {
  FrameInputs inputs = inputs_of(320, 180, 89);
  for (const std::string& preset : restir_preset_names()) {
    EXPECT_EQ(restir_preset(preset).reservoir_stride, 1u) << preset;
    const gpu::RestirPush push = RestirIntegrator::make_push(restir_preset(preset), inputs);
    EXPECT_EQ(push.reservoir_stride, 1u);
    EXPECT_EQ(push.representative, 0u);
  }
  for (std::uint32_t stride : {2u, 3u, 4u}) {
    const RestirSettings s =
        make_restir_settings("balanced", {{"reservoir_stride", std::to_string(stride)}});
    std::vector<int> visits(stride * stride, 0);
    for (std::uint32_t frame = 0; frame < stride * stride; ++frame) {
      inputs.frame_index = 100 + frame;
      const gpu::RestirPush push = RestirIntegrator::make_push(s, inputs);
      EXPECT_EQ(push.reservoir_stride, stride);
      const std::uint32_t x = push.representative & 0xffffu;
      const std::uint32_t y = push.representative >> 16;
      ASSERT_LT(x, stride);
      ASSERT_LT(y, stride);
      ++visits[y * stride + x];
    }
    EXPECT_EQ(std::count(visits.begin(), visits.end(), 1), static_cast<long>(stride * stride))
        << "stride " << stride << ": every offset once";
  }
  try {
    make_restir_settings("balanced", {{"reservoir_stride", "2"}, {"visibility_reuse", "4"}});
    ADD_FAILURE() << "visibility_reuse with reservoir_stride 2 was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("visibility_reuse"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("reservoir_stride"), std::string::npos) << e.what();
  }
  // The play panel sets fields directly: the passes then keep no verdict.
  RestirSettings both = make_restir_settings("balanced", {{"reservoir_stride", "2"}});
  both.visibility_reuse = 4;
  EXPECT_EQ(RestirIntegrator::make_push(both, inputs).visibility_reuse, 0u);
}

}  // namespace
}  // namespace lantern::lighting
