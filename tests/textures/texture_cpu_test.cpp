// Textures on the CPU: image decoding (PNG, JPEG, EXR; file, data URI, buffer view) and its bad
// input (missing, truncated, undecodable, beyond the size cap), the glTF import of texture
// references (sampler, KHR_texture_transform, TEXCOORD_0/1, alpha modes; a texcoord set the
// primitive lacks), the texture set (sRGB -> linear by use, mip chains in linear light, wrap
// modes and the transform), the emission integral over a triangle and the light power it gives,
// vertex tangents (the asset's TANGENT, generated ones, and which vertices the scene uploads).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "engine/core/error.h"
#include "engine/level/level_loader.h"
#include "engine/level/primitives.h"
#include "engine/scene/mesh_tangents.h"
#include "lighting/scene/scene_data.h"
#include "lighting/textures/texture_set.h"
#include "runtime/image/image_decode.h"
#include "runtime/image/image_encode.h"
#include "tests/runtime/scratch_dir.h"
#include "tests/textures/textured_assets.h"

namespace lantern {
namespace {

namespace fs = std::filesystem;
using test::ImageStorage;
using test::TexturedQuadOptions;

fs::path scratch(const std::string& name) {
  return lantern::test::process_scratch_dir() / name;
}

template <class F>
std::string input_error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected InputError";
  return {};
}

double srgb_decode(double c) {  // IEC 61966-2-1, written out here
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

std::vector<std::uint8_t> gradient_rgba8(std::uint32_t w, std::uint32_t h) {
  return test::make_rgba8(w, h, [&](std::uint32_t x, std::uint32_t y) {
    return glm::vec4(static_cast<float>(x) / static_cast<float>(w - 1),
                     static_cast<float>(y) / static_cast<float>(h - 1), 0.25f, 1.0f);
  });
}

Level load_quad(const TexturedQuadOptions& o, const std::string& name) {
  const fs::path file = scratch(name + ".gltf");
  std::ofstream(file) << test::textured_quad_gltf(o).dump();
  return load_level(file);
}

TEST(ImageDecode, PngDecodesAsStored) {
  const std::vector<std::uint8_t> texels = {0,   64, 128, 255, 10,  20,  30,  40,
                                            255, 0,  0,   255, 188, 188, 188, 255};
  const runtime::DecodedImage img =
      runtime::decode_image_bytes(test::png_of(2, 2, texels), "image/png", 64, "png");
  ASSERT_EQ(img.width, 2u);
  ASSERT_EQ(img.height, 2u);
  EXPECT_FALSE(img.high_dynamic_range);
  for (std::size_t i = 0; i < texels.size(); ++i)
    EXPECT_NEAR(img.rgba[i], texels[i] / 255.0f, 1e-6f) << i;
}

TEST(ImageDecode, JpegAndHalfExrAndSignatureSniffing) {
  const auto flat =
      test::make_rgba8(8, 8, [](auto, auto) { return glm::vec4(0.5f, 0.25f, 0.75f, 1); });
  const std::vector<std::uint8_t> jpeg = runtime::encode_rgba8(8, 8, flat, ".jpg");
  const runtime::DecodedImage j = runtime::decode_image_bytes(jpeg, "", 64, "jpeg");  // sniffed
  EXPECT_NEAR(j.at(3, 3)[0], 0.5f, 0.02f);
  EXPECT_NEAR(j.at(3, 3)[2], 0.75f, 0.02f);
  EXPECT_FLOAT_EQ(j.at(3, 3)[3], 1.0f);  // no alpha in JPEG

  std::vector<float> hdr(4 * 4 * 2, 1.0f);
  hdr[0] = 12.5f;  // beyond [0, 1]: kept
  const runtime::DecodedImage e =
      runtime::decode_image_bytes(runtime::encode_exr(4, 2, hdr), "image/x-exr", 64, "exr");
  EXPECT_TRUE(e.high_dynamic_range);
  EXPECT_FLOAT_EQ(e.at(0, 0)[0], 12.5f);
}

TEST(ImageDecode, BadInputIsOneErrorNamingTheImage) {
  const std::vector<std::uint8_t> png = test::png_of(16, 16, gradient_rgba8(16, 16));
  std::vector<std::uint8_t> truncated(png.begin(), png.begin() + static_cast<long>(png.size() / 2));
  EXPECT_NE(input_error_of([&] {
              runtime::decode_image_bytes(truncated, "image/png", 64, "sign.png");
            }).find("sign.png"),
            std::string::npos);
  const std::vector<std::uint8_t> garbage(200, 0x5a);
  EXPECT_NE(input_error_of([&] {
              runtime::decode_image_bytes(garbage, "", 64, "x");
            }).find("not PNG, JPEG or EXR"),
            std::string::npos);
  EXPECT_NE(input_error_of([&] { runtime::decode_image_bytes(garbage, "image/png", 64, "x"); }),
            "");
  EXPECT_NE(input_error_of([&] {
              runtime::decode_image_bytes({}, "image/png", 64, "x");
            }).find("no bytes"),
            std::string::npos);
  const std::vector<std::uint8_t> wide = test::png_of(65, 1, std::vector<std::uint8_t>(65 * 4, 9));
  EXPECT_NE(input_error_of([&] {
              runtime::decode_image_bytes(wide, "image/png", 64, "wide");
            }).find("larger than the 64x64 texture limit"),
            std::string::npos);
  // An EXR header attribute claiming more bytes than the file has is refused before OpenEXR
  // allocates it (the fuzzer's out-of-memory input: a 1.7 GB attribute in 613 bytes).
  std::vector<float> flat_texels(4 * 4, 0.5f);
  std::vector<std::uint8_t> exr = runtime::encode_exr(2, 2, flat_texels);
  std::size_t size_at = 8;  // magic + version; then the first attribute's name\0 type\0
  for (int strings = 0; strings < 2; ++size_at)
    if (exr.at(size_at) == 0) ++strings;
  const std::uint32_t huge = 0x7fff0000u;
  std::memcpy(exr.data() + size_at, &huge, 4);
  EXPECT_NE(input_error_of([&] { runtime::decode_image_bytes(exr, "image/x-exr", 64, "x"); })
                .find("malformed EXR header"),
            std::string::npos);
  EXPECT_NE(input_error_of([&] {
              runtime::decode_image_file(scratch("none.png"), 64, "m");
            }).find("not found"),
            std::string::npos);
}

// KTX2 (image/ktx2, KHR_texture_basisu): OpenImageIO 2.4 has no reader, so a KTX2 image, by
// MIME type, signature or file name, is one error that says so and names the image, and a glTF
// texture whose only source is KHR_texture_basisu is refused at import.
TEST(ImageDecode, Ktx2IsRefusedWithTheReason) {
  std::vector<std::uint8_t> ktx2 = {0xab, 'K', 'T', 'X', ' ', '2', '0', 0xbb, '\r', '\n', 0x1a, '\n'};
  ktx2.resize(256, 0);
  for (const char* mime : {"image/ktx2", ""}) {
    const std::string e =
        input_error_of([&] { runtime::decode_image_bytes(ktx2, mime, 64, "signs.ktx2"); });
    EXPECT_NE(e.find("KTX2"), std::string::npos) << e;
    EXPECT_NE(e.find("signs.ktx2"), std::string::npos) << e;
  }
  const fs::path file = scratch("panel.ktx2");
  std::ofstream(file, std::ios::binary)
      .write(reinterpret_cast<const char*>(ktx2.data()), static_cast<std::streamsize>(ktx2.size()));
  const std::string e = input_error_of([&] { runtime::decode_image_file(file, 64, "panel"); });
  EXPECT_NE(e.find("KTX2"), std::string::npos) << e;
  EXPECT_NE(e.find("panel.ktx2"), std::string::npos) << e;

  TexturedQuadOptions o;
  o.image_bytes = test::png_of(4, 4, gradient_rgba8(4, 4));
  nlohmann::json doc = test::textured_quad_gltf(o);
  doc["textures"][0].erase("source");
  doc["textures"][0]["extensions"] = {{"KHR_texture_basisu", {{"source", 0}}}};
  doc["extensionsUsed"] = {"KHR_texture_basisu"};
  const fs::path gltf = scratch("basisu.gltf");
  std::ofstream(gltf) << doc.dump();
  const std::string g = input_error_of([&] { load_level(gltf); });
  EXPECT_NE(g.find("KHR_texture_basisu"), std::string::npos) << g;
  EXPECT_NE(g.find("basisu.gltf"), std::string::npos) << g;
}

TEST(GltfTextures, ImagesFromDataUriBufferViewAndFileDecodeAlike) {
  const std::vector<std::uint8_t> texels = gradient_rgba8(8, 4);
  TexturedQuadOptions o;
  o.image_bytes = test::png_of(8, 4, texels);
  std::vector<glm::vec4> first;
  for (ImageStorage storage :
       {ImageStorage::DataUri, ImageStorage::BufferView, ImageStorage::File}) {
    o.storage = storage;
    o.image_file = scratch("quad_image.png");
    const Level level = load_quad(o, "storage");
    ASSERT_EQ(level.images.size(), 1u);
    const lighting::TextureSet set = lighting::TextureSet::build(level);
    ASSERT_EQ(set.images().size(), 1u);
    const lighting::TextureImage& img = set.images()[0];
    EXPECT_EQ(img.width, 8u);
    EXPECT_EQ(img.height, 4u);
    EXPECT_EQ(img.levels, 4u);  // 8x4, 4x2, 2x1, 1x1
    if (first.empty()) first = img.linear;
    EXPECT_EQ(img.linear, first);
  }
}

TEST(GltfTextures, SamplerTransformTexcoordSetsAndAlphaModes) {
  TexturedQuadOptions o;
  o.image_bytes = test::png_of(4, 4, gradient_rgba8(4, 4));
  o.sampler = {{"magFilter", 9728}, {"minFilter", 9985}, {"wrapS", 33071}, {"wrapT", 33648}};
  o.texture_transform = {
      {"offset", {0.5, 0.25}}, {"rotation", 0.5}, {"scale", {2.0, 3.0}}, {"texCoord", 1}};
  o.with_texcoord1 = true;
  o.alpha_mode = "BLEND";
  const Level level = load_quad(o, "sampler");
  const Material& m = level.materials[level.instances[0].material];
  const TextureRef& t = m.base_color_texture;
  EXPECT_EQ(t.sampler.wrap_s, TextureWrap::ClampToEdge);
  EXPECT_EQ(t.sampler.wrap_t, TextureWrap::MirroredRepeat);
  EXPECT_FALSE(t.sampler.mag_linear);
  EXPECT_TRUE(t.sampler.min_linear);  // LINEAR_MIPMAP_NEAREST
  EXPECT_TRUE(t.sampler.mipmaps);
  EXPECT_FALSE(t.sampler.mip_linear);
  EXPECT_EQ(t.offset, glm::vec2(0.5f, 0.25f));
  EXPECT_FLOAT_EQ(t.rotation, 0.5f);
  EXPECT_EQ(t.scale, glm::vec2(2.0f, 3.0f));
  EXPECT_EQ(t.texcoord, 1u);  // the transform's texCoord overrides
  EXPECT_EQ(m.alpha_mode, AlphaMode::Blend);
  EXPECT_FLOAT_EQ(m.alpha_cutoff, 0.5f);
  // The mesh carries TEXCOORD_0 and, since a texture samples it, TEXCOORD_1 (2 x set 0 here).
  const Mesh& mesh = level.meshes[level.instances[0].mesh];
  ASSERT_EQ(mesh.uvs.size(), 4u);
  ASSERT_EQ(mesh.uvs1.size(), 4u);
  EXPECT_EQ(mesh.uvs[2], glm::vec2(1.0f, 0.0f));
  EXPECT_EQ(mesh.uvs1[2], glm::vec2(2.0f, 2.0f));
  EXPECT_EQ(&mesh.texcoords(1), &mesh.uvs1);

  // The transform, as the GPU and CPU samplers apply it: T(offset) R(rotation) S(scale).
  const lighting::TextureSet set = lighting::TextureSet::build(level);
  const gpu::GpuTexture& g = set.records()[0];
  const glm::vec2 uv(0.3f, 0.7f);
  const glm::vec2 s = uv * glm::vec2(2.0f, 3.0f);
  const float c = std::cos(0.5f), sn = std::sin(0.5f);
  const glm::vec2 expected =
      glm::vec2(c * s.x - sn * s.y, sn * s.x + c * s.y) + glm::vec2(0.5f, 0.25f);
  const glm::vec2 got = gpu::texture_transform_uv(g, uv);
  EXPECT_NEAR(got.x, expected.x, 1e-5f);
  EXPECT_NEAR(got.y, expected.y, 1e-5f);
  EXPECT_EQ(g.format.y, gpu::kWrapClamp);
  EXPECT_EQ(g.format.z, gpu::kWrapMirror);
}

// A material whose textures mix sets: base colour on TEXCOORD_0, emission on TEXCOORD_1. Both
// sets load, the scene uploads set 1 for every vertex, and the textured light's uvs are set 1's.
TEST(GltfTextures, MaterialMayMixTexcoordSets) {
  TexturedQuadOptions o;
  o.image_bytes = test::png_of(4, 4, gradient_rgba8(4, 4));
  o.with_texcoord1 = true;
  nlohmann::json doc = test::textured_quad_gltf(o);
  doc["materials"][0]["emissiveTexture"] = {{"index", 0}, {"texCoord", 1}};
  doc["materials"][0]["emissiveFactor"] = {1.0, 1.0, 1.0};
  const fs::path file = scratch("mixed_sets.gltf");
  std::ofstream(file) << doc.dump();
  const Level level = load_level(file);
  const Material& m = level.materials[level.instances[0].material];
  EXPECT_EQ(m.base_color_texture.texcoord, 0u);
  EXPECT_EQ(m.emissive_texture.texcoord, 1u);
  const Mesh& mesh = level.meshes[level.instances[0].mesh];
  ASSERT_EQ(mesh.uvs.size(), 4u);
  ASSERT_EQ(mesh.uvs1.size(), 4u);
  const lighting::SceneData scene = lighting::build_scene_data(level);
  ASSERT_EQ(scene.vertex_texcoords1.size(), scene.vertices.size());
  for (std::size_t v = 0; v < mesh.uvs1.size(); ++v) EXPECT_EQ(scene.vertex_texcoords1[v], mesh.uvs1[v]);
  ASSERT_EQ(scene.textured_emitters.size(), 2u);
  const std::uint32_t v0 = mesh.indices[0];
  EXPECT_EQ(glm::vec2(scene.textured_emitters[0].uv01), mesh.uvs1[v0]);
  const std::vector<gpu::GpuTexture>& records = scene.textures.records();
  const glm::uvec4 slots = scene.textures.material_textures(level.instances[0].material);
  EXPECT_EQ(records[slots.x].transform_u.w, 0.0f);
  EXPECT_EQ(records[slots.z].transform_u.w, 1.0f);
  // Without set 1 in any texture, nothing is uploaded for it.
  TexturedQuadOptions plain;
  plain.image_bytes = o.image_bytes;
  plain.with_texcoord1 = true;
  EXPECT_TRUE(lighting::build_scene_data(load_quad(plain, "set0_only")).vertex_texcoords1.empty());
}

TEST(GltfTextures, MissingTexcoordSetIsAnError) {
  TexturedQuadOptions o;
  o.image_bytes = test::png_of(4, 4, gradient_rgba8(4, 4));
  o.texcoord = 1;  // TEXCOORD_1 is not in the primitive
  std::string e = input_error_of([&] { load_quad(o, "no_set1"); });
  EXPECT_NE(e.find("TEXCOORD_1"), std::string::npos) << e;
  EXPECT_NE(e.find("no_set1.gltf"), std::string::npos) << e;
  o.texcoord = 0;
  o.omit_texcoords = true;
  e = input_error_of([&] { load_quad(o, "no_set0"); });
  EXPECT_NE(e.find("TEXCOORD_0"), std::string::npos) << e;
  o.omit_texcoords = false;
  o.texcoord = 2;
  e = input_error_of([&] { load_quad(o, "set2"); });
  EXPECT_NE(e.find("TEXCOORD_2"), std::string::npos) << e;
}

TEST(GltfTextures, UndecodableImageNamesFileAndMaterialSlot) {
  TexturedQuadOptions o;
  o.image_bytes = test::png_of(16, 16, gradient_rgba8(16, 16));
  o.image_bytes.resize(o.image_bytes.size() / 3);  // truncated PNG
  const Level level = load_quad(o, "truncated");
  const std::string e = input_error_of([&] { lighting::build_scene_data(level); });
  EXPECT_NE(e.find("truncated.gltf"), std::string::npos) << e;
  EXPECT_NE(e.find("baseColorTexture"), std::string::npos) << e;
  o.storage = ImageStorage::File;
  o.image_file = scratch("gone.png");
  o.image_bytes = test::png_of(4, 4, gradient_rgba8(4, 4));
  const fs::path file = scratch("missing_file.gltf");
  std::ofstream(file) << test::textured_quad_gltf(o).dump();
  fs::remove(o.image_file);
  EXPECT_NE(input_error_of([&] { load_level(file); }).find("gone.png"), std::string::npos);
}

// sRGB for base colour and emission, linear for data; mips in linear light.
TEST(TextureSet, ColourSpaceByUseAndMipChain) {
  Level level;
  const auto texels = test::make_rgba8(4, 2, [](std::uint32_t x, std::uint32_t) {
    return glm::vec4(x < 2 ? 188.0f / 255.0f : 0.0f, 1.0f, 0.0f, 1.0f);
  });
  const std::int32_t image = test::add_png(level, 4, 2, texels);
  Material m = make_lambert(1.0f);
  m.base_color_texture.image = image;
  m.metallic_roughness_texture.image = image;
  level.materials.push_back(m);
  const lighting::TextureSet set = lighting::TextureSet::build(level);
  ASSERT_EQ(set.images().size(), 2u);  // one image, two colour spaces
  const lighting::TextureImage& colour = set.image_of(set.material_textures(0).x);
  const lighting::TextureImage& data = set.image_of(set.material_textures(0).y);
  EXPECT_TRUE(colour.srgb);
  EXPECT_EQ(colour.format, gpu::kTexelHalf);  // decoded at load, kept linear
  EXPECT_EQ(data.format, gpu::kTexelUnorm8);
  EXPECT_NEAR(colour.linear[0].r, srgb_decode(188.0 / 255.0), 1e-6);
  EXPECT_NEAR(data.linear[0].r, 188.0 / 255.0, 1e-6);
  EXPECT_EQ(set.material_textures(0).z, gpu::kNoTexture);
  // 4x2 -> 2x1 -> 1x1: 3 levels; the last is the mean of level 0 in linear light.
  EXPECT_EQ(colour.levels, 3u);
  const std::uint32_t last = colour.first_word + 2 * (4 * 2 + 2 * 1);  // two words per texel
  const glm::vec2 stored = glm::unpackHalf2x16(set.texels()[last]);
  EXPECT_NEAR(stored.x, 0.5 * srgb_decode(188.0 / 255.0), 1e-3);
  EXPECT_EQ(set.texel_bytes(), (2u + 1u) * (8 + 2 + 1) * 4);  // half (colour) + rgba8 (data)
}

TEST(TextureSet, WrapModesAndBilinear) {
  EXPECT_EQ(gpu::texture_wrap(-1, 4, gpu::kWrapRepeat), 3);
  EXPECT_EQ(gpu::texture_wrap(5, 4, gpu::kWrapRepeat), 1);
  EXPECT_EQ(gpu::texture_wrap(-1, 4, gpu::kWrapClamp), 0);
  EXPECT_EQ(gpu::texture_wrap(9, 4, gpu::kWrapClamp), 3);
  EXPECT_EQ(gpu::texture_wrap(4, 4, gpu::kWrapMirror), 3);
  EXPECT_EQ(gpu::texture_wrap(-1, 4, gpu::kWrapMirror), 0);
  EXPECT_EQ(gpu::texture_wrap(-5, 4, gpu::kWrapMirror), 3);
  Level level;
  const auto texels = test::make_rgba8(2, 1, [](std::uint32_t x, std::uint32_t) {
    return glm::vec4(x == 0 ? 0.0f : 1.0f, 0, 0, 1);
  });
  Material m = make_lambert(1.0f);
  m.metallic_roughness_texture.image = test::add_png(level, 2, 1, texels);  // linear
  level.materials.push_back(m);
  const lighting::TextureSet set = lighting::TextureSet::build(level);
  const std::uint32_t r = set.material_textures(0).y;
  EXPECT_NEAR(set.sample(r, {0.25f, 0.5f}).r, 0.0f, 1e-6f);  // texel 0 centre
  EXPECT_NEAR(set.sample(r, {0.5f, 0.5f}).r, 0.5f, 1e-6f);   // between the texels
  EXPECT_NEAR(set.sample(r, {0.0f, 0.5f}).r, 0.5f, 1e-6f);   // repeat: blends texel 1
}

// The mean of a texture over a triangle: a ramp in u has the value at the centroid.
TEST(TextureSet, EmissionIntegralOverTriangle) {
  Level level;
  const std::uint32_t w = 64;
  const auto texels = test::make_rgba8(w, 1, [&](std::uint32_t x, std::uint32_t) {
    return glm::vec4(static_cast<float>(x) / (w - 1), 0.5f, 0, 1);
  });
  Material m = make_lambert(1.0f);
  m.metallic_roughness_texture.image = test::add_png(level, w, 1, texels);
  m.metallic_roughness_texture.sampler.wrap_s = TextureWrap::ClampToEdge;
  level.materials.push_back(m);
  const lighting::TextureSet set = lighting::TextureSet::build(level);
  const std::uint32_t r = set.material_textures(0).y;
  const glm::vec2 a(0.1f, 0.0f), b(0.9f, 0.2f), c(0.5f, 0.9f);
  const glm::vec3 mean = lighting::integrate_texture_over_triangle(set, r, a, b, c);
  // Texel centres map u -> (u * w - 0.5) / (w - 1) on the ramp (8-bit quantised: 1/510).
  const double u = (a.x + b.x + c.x) / 3.0;
  EXPECT_NEAR(mean.r, (u * w - 0.5) / (w - 1), 2.5e-3);
  EXPECT_NEAR(mean.g, 128.0 / 255.0, 1e-6);
}

// Emissive textured triangles: power = luminance(factor x texture mean) x area x pi; a triangle
// over black texels has power 0 (never sampled), and each record names its texture record.
TEST(TextureSet, TexturedEmitterPowerFollowsTheTexture) {
  Level level;
  level.meshes.push_back(make_plane(glm::vec2(2.0f, 2.0f)));  // two triangles, uv 0..1
  const auto texels = test::make_rgba8(16, 16, [](std::uint32_t x, std::uint32_t y) {
    return x >= y ? glm::vec4(0, 0, 0, 1)
                  : glm::vec4(1, 1, 1, 1);  // black on and above the diagonal
  });
  Material emitter = make_lambert(0.0f);
  emitter.emissive_factor = glm::vec3(2.0f);
  emitter.emissive_texture.image = test::add_png(level, 16, 16, texels);
  emitter.emissive_texture.sampler.mag_linear = false;
  level.materials.push_back(emitter);
  Instance inst;
  inst.mesh = 0;
  inst.material = 0;
  level.instances.push_back(inst);
  const lighting::SceneData scene = lighting::build_scene_data(level);
  ASSERT_EQ(scene.textured_emitters.size(), 2u);
  ASSERT_EQ(scene.lights.lights().size(), 2u);
  const std::vector<lighting::LightEmitter> emitters =
      lighting::extract_light_emitters(level, scene.scene_radius(), &scene);
  ASSERT_EQ(emitters.size(), 2u);
  std::array<float, 2> powers{};
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(glm::floatBitsToUint(emitters[i].light.radiance.w) - 1u, i);
    powers[i] = emitters[i].power;
  }
  // The plane's uv diagonal splits it: one triangle lies on black texels only (u >= v), the
  // other on white ones but for the halves of the (black) diagonal texels it covers.
  const float area = 2.0f;  // each triangle: half of 2 x 2
  const float white = std::max(powers[0], powers[1]);
  const float black = std::min(powers[0], powers[1]);
  EXPECT_NEAR(white, 2.0f * area * 3.14159265f, 0.1f * 2.0f * area * 3.14159265f);
  EXPECT_GT(white, 0.0f);
  EXPECT_EQ(black, 0.0f);
  // Fully black: exactly zero.
  Level dark = level;
  dark.images.clear();
  dark.materials[0].emissive_texture.image = test::add_png(
      dark, 4, 4, test::make_rgba8(4, 4, [](auto, auto) { return glm::vec4(0, 0, 0, 1); }));
  const lighting::SceneData dark_scene = lighting::build_scene_data(dark);
  for (const lighting::LightEmitter& e :
       lighting::extract_light_emitters(dark, dark_scene.scene_radius(), &dark_scene))
    EXPECT_EQ(e.power, 0.0f);
  EXPECT_FALSE(dark_scene.lights.has_power());
}

TEST(TextureSet, UntexturedLevelBuildsNothing) {
  Level level;
  level.meshes.push_back(make_plane(glm::vec2(2.0f, 2.0f)));
  level.materials.push_back(make_lambert(0.5f));
  Instance inst;
  level.instances.push_back(inst);
  const lighting::SceneData scene = lighting::build_scene_data(level);
  EXPECT_TRUE(scene.textures.empty());
  EXPECT_TRUE(scene.textures.texels().empty());
  EXPECT_TRUE(scene.textured_emitters.empty());
  EXPECT_EQ(scene.materials[0].textures, glm::uvec4(gpu::kNoTexture));
  EXPECT_EQ(scene.materials[0].params.w, 0.0f);
  EXPECT_EQ(scene.materials[0].emission.w, 0.0f);
}

// Generated tangents follow +u in the normal's plane, with glTF's handedness (up = w x
// cross(n, t) points towards decreasing v), on a plane and on a smooth sphere.
TEST(VertexTangents, GeneratedFramesFollowTheUvMapping) {
  const Mesh plane = make_plane(glm::vec2(2.0f, 2.0f));
  ASSERT_EQ(plane.uvs.size(), plane.positions.size());
  const std::vector<glm::vec4> pt = generate_tangents(plane);
  ASSERT_EQ(pt.size(), plane.positions.size());
  for (std::size_t v = 0; v < pt.size(); ++v) {
    const glm::vec3 t(pt[v]);
    EXPECT_NEAR(glm::length(t), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(t, plane.normals[v]), 0.0f, 1e-5f);
    ASSERT_NE(pt[v].w, 0.0f);
  }
  // Finite differences of the mapping on triangle 0: du along t, and "up" against dv.
  const std::uint32_t a = plane.indices[0], b = plane.indices[1], c = plane.indices[2];
  const glm::vec3 e1 = plane.positions[b] - plane.positions[a];
  const glm::vec3 e2 = plane.positions[c] - plane.positions[a];
  const glm::vec2 d1 = plane.uvs[b] - plane.uvs[a], d2 = plane.uvs[c] - plane.uvs[a];
  const float det = d1.x * d2.y - d1.y * d2.x;
  const glm::vec3 dp_du = glm::normalize((e1 * d2.y - e2 * d1.y) / det);
  const glm::vec3 dp_dv = glm::normalize((e2 * d1.x - e1 * d2.x) / det);
  EXPECT_NEAR(glm::dot(glm::vec3(pt[a]), dp_du), 1.0f, 1e-5f);
  const glm::vec3 up = pt[a].w * glm::cross(plane.normals[a], glm::vec3(pt[a]));
  EXPECT_NEAR(glm::dot(up, dp_dv), -1.0f, 1e-5f);

  // A sphere: unit, orthogonal to the smooth normals, and smooth (neighbours within a few
  // degrees) away from the poles, where the uv mapping degenerates.
  const Mesh sphere = make_uv_sphere(1.0f, 48, 24);
  const std::vector<glm::vec4> st = generate_tangents(sphere);
  std::size_t checked = 0;
  for (std::size_t t = 0; t < sphere.indices.size(); t += 3) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = sphere.indices[t + static_cast<std::size_t>(k)];
      const std::uint32_t w = sphere.indices[t + static_cast<std::size_t>((k + 1) % 3)];
      if (std::abs(sphere.normals[v].y) > 0.9f || std::abs(sphere.normals[w].y) > 0.9f) continue;
      ASSERT_NE(st[v].w, 0.0f);
      EXPECT_NEAR(glm::length(glm::vec3(st[v])), 1.0f, 1e-4f);
      EXPECT_NEAR(glm::dot(glm::vec3(st[v]), sphere.normals[v]), 0.0f, 1e-4f);
      EXPECT_EQ(st[v].w, st[w].w);
      EXPECT_GT(glm::dot(glm::vec3(st[v]), glm::vec3(st[w])), std::cos(0.2f));
      ++checked;
    }
  }
  EXPECT_GT(checked, 1000u);
}

// The asset's TANGENT is read (normalised, w to +-1); NaN is one error naming the file.
TEST(VertexTangents, GltfTangentAttributeIsReadAndChecked) {
  TexturedQuadOptions o;
  o.image_bytes = test::png_of(4, 4, gradient_rgba8(4, 4));
  o.tangent = glm::vec4(0.0f, 2.0f, 0.0f, -0.5f);
  const Level level = load_quad(o, "tangent");
  const Mesh& mesh = level.meshes[level.instances[0].mesh];
  ASSERT_EQ(mesh.tangents.size(), 4u);
  for (const glm::vec4& t : mesh.tangents) EXPECT_EQ(t, glm::vec4(0.0f, 1.0f, 0.0f, -1.0f));
  o.tangent = glm::vec4(std::nanf(""), 0.0f, 0.0f, 1.0f);
  const std::string e = input_error_of([&] { load_quad(o, "nan_tangent"); });
  EXPECT_NE(e.find("nan_tangent.gltf"), std::string::npos) << e;
  EXPECT_NE(e.find("tangent"), std::string::npos) << e;
}

// The scene uploads tangents only when a material has a normal texture, and then for the meshes
// it maps: the asset's own where given, generated otherwise, zero (no frame) for the rest.
TEST(VertexTangents, SceneUploadsTangentsOnlyForNormalMappedMeshes) {
  Level level;
  level.meshes.push_back(make_plane(glm::vec2(2.0f, 2.0f)));
  level.meshes.push_back(make_plane(glm::vec2(1.0f, 1.0f)));
  level.materials.push_back(make_lambert(0.5f));
  level.instances.push_back(Instance{});
  EXPECT_TRUE(lighting::build_scene_data(level).vertex_tangents.empty());

  Material mapped = make_lambert(0.5f);
  mapped.normal_texture.image = test::add_png(
      level, 2, 2, test::make_rgba8(2, 2, [](auto, auto) { return glm::vec4(0.5f, 0.5f, 1, 1); }));
  level.materials.push_back(mapped);
  Instance second;
  second.mesh = 1;
  second.material = 1;
  level.instances.push_back(second);
  level.meshes[1].tangents.assign(level.meshes[1].positions.size(), glm::vec4(0, 0, 1, -1));
  const lighting::SceneData scene = lighting::build_scene_data(level);
  const std::size_t n0 = level.meshes[0].positions.size();
  ASSERT_EQ(scene.vertex_tangents.size(), scene.vertices.size());
  for (std::size_t v = 0; v < scene.vertex_tangents.size(); ++v)
    EXPECT_EQ(scene.vertex_tangents[v],
              v < n0 ? gpu::vec4(0.0f) : gpu::vec4(0.0f, 0.0f, 1.0f, -1.0f));
  // Without the asset's tangents the mapped mesh gets generated ones.
  level.meshes[1].tangents.clear();
  const std::vector<glm::vec4> generated = generate_tangents(level.meshes[1]);
  const lighting::SceneData regenerated = lighting::build_scene_data(level);
  for (std::size_t v = 0; v < generated.size(); ++v)
    EXPECT_EQ(regenerated.vertex_tangents[n0 + v], generated[v]);
}

}  // namespace
}  // namespace lantern
