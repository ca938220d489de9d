// The material textures of a level, ready to upload: every referenced image (by file or by
// embedded bytes: duplicates are decoded once) decoded once per colour space it is used in (sRGB
// for base colour and emission, as glTF requires; linear for metallic-roughness and normals), its
// mip chain box-filtered in linear light, packed into one texel array (shared/textures.h encodings:
// RGBA8 sRGB / RGBA8 linear / RGBA16F for HDR sources), and one GpuTexture record per material
// texture slot (image + glTF sampler + KHR_texture_transform). A level without textures builds
// nothing (empty arrays).
//
// Why a texel array sampled in software rather than a bindless array of sampled images
// (descriptor indexing) or an atlas, by measurement on lavapipe 25 (tests/textures/
// texture_sampling_bench, README "Measured"): a hardware bilinear sample costs 3-11 ns, the
// software one 16-30 ns (rgba8 / rgba16f; 53 ns for sRGB8 decoded per texel, hence colour is
// stored linear in half floats), so a fully textured G-buffer costs 3-4x an untextured one here.
// The software path is kept because the same record + array is read by every stage that needs a
// texture -- the forward G-buffer fragment shader, the visibility resolve, the BVH's alpha test
// inside compute traversal and the light evaluation of every integrator -- through the one
// scene-buffer table (one slot per buffer, bound by name with the push descriptors every pass
// uses), without samplers, image layouts or a second descriptor kind in the render graph. A
// bindless array needs a descriptor-set path beside the push descriptors (they hold no large
// arrays), bound in all those passes; an atlas needs padding for wrap modes and mips and still
// software wrap. Where G-buffer time matters (real GPUs, texture-heavy frames) the bindless array
// goes behind lib/textures.glsl's texture_sample_record, the G-buffer first.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "engine/scene/level.h"
#include "shared/textures.h"

namespace lantern::lighting {

// One decoded image in one colour space, as stored in the texel array.
struct TextureImage {
  std::uint32_t image = 0;  // Level::images index
  bool srgb = false;        // decoded as sRGB colour (base colour, emission)
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::uint32_t levels = 0;
  std::uint32_t format = gpu::kTexelUnorm8;
  std::uint32_t first_word = 0;
  std::uint64_t bytes = 0;        // all levels in the texel array
  std::vector<glm::vec4> linear;  // level 0, linear RGBA (for integrating emission on the CPU)
};

class TextureSet {
 public:
  TextureSet() = default;
  // Decodes every image a material uses. lantern::InputError naming the image (and the material
  // slot using it) for a missing, truncated or undecodable file, an image beyond
  // kMaxTextureSide, or a level whose texels exceed kMaxTexelBytes.
  static TextureSet build(const Level& level);

  const std::vector<gpu::GpuTexture>& records() const { return records_; }
  const std::vector<std::uint32_t>& texels() const { return texels_; }
  const std::vector<TextureImage>& images() const { return images_; }
  // Per material: GpuMaterial.textures (base colour, metallic-roughness, emissive, normal).
  const glm::uvec4& material_textures(std::size_t material) const { return material_[material]; }
  bool empty() const { return records_.empty(); }
  std::uint64_t texel_bytes() const { return texels_.size() * sizeof(std::uint32_t); }
  // Wall time build() took (decode, colour conversion, mip chains, packing).
  double build_ms() const { return build_ms_; }

  // Level-0 bilinear sample of record `record` at mesh texcoord `uv` (transform, wrap applied),
  // linear RGBA: what the GPU's texture_sample returns at lod 0, on the CPU.
  glm::vec4 sample(std::uint32_t record, glm::vec2 uv) const;
  // The image behind record `record`.
  const TextureImage& image_of(std::uint32_t record) const;

 private:
  std::vector<gpu::GpuTexture> records_;
  std::vector<std::uint32_t> record_image_;  // per record: images_ index
  std::vector<std::uint32_t> texels_;
  std::vector<TextureImage> images_;
  std::vector<glm::uvec4> material_;
  double build_ms_ = 0.0;
};

// The mean of `texture` (a record of `set`) over the triangle with texcoords uv0..uv2: the
// emissive factor's weight for a textured triangle light's power. Stratified over a barycentric
// grid fine enough for the triangle's texel footprint (at most 64 x 64 cells).
glm::vec3 integrate_texture_over_triangle(const TextureSet& set, std::uint32_t texture,
                                          glm::vec2 uv0, glm::vec2 uv1, glm::vec2 uv2);

}  // namespace lantern::lighting
