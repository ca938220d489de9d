// Level images -> texel array + texture records (texture_set.h).
#include "lighting/textures/texture_set.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include "engine/core/error.h"
#include "runtime/image/image_decode.h"
#include "shared/scene.h"

namespace lantern::lighting {
namespace {

std::uint32_t wrap_mode(TextureWrap w) {
  switch (w) {
    case TextureWrap::ClampToEdge:
      return gpu::kWrapClamp;
    case TextureWrap::MirroredRepeat:
      return gpu::kWrapMirror;
    case TextureWrap::Repeat:
      break;
  }
  return gpu::kWrapRepeat;
}

std::uint32_t filter_bits(const TextureSampler& s) {
  return (s.mag_linear ? gpu::kFilterMagLinear : 0u) | (s.min_linear ? gpu::kFilterMinLinear : 0u) |
         (s.mip_linear ? gpu::kFilterMipLinear : 0u) | (s.mipmaps ? gpu::kFilterMipmaps : 0u);
}

// The next mip level: 2x2 box filter in linear light (odd sides drop their last row/column).
std::vector<glm::vec4> downsample(const std::vector<glm::vec4>& src, std::uint32_t w,
                                  std::uint32_t h, std::uint32_t nw, std::uint32_t nh) {
  std::vector<glm::vec4> out(std::size_t{nw} * nh);
  for (std::uint32_t y = 0; y < nh; ++y)
    for (std::uint32_t x = 0; x < nw; ++x) {
      const std::uint32_t x0 = std::min(2 * x, w - 1), x1 = std::min(2 * x + 1, w - 1);
      const std::uint32_t y0 = std::min(2 * y, h - 1), y1 = std::min(2 * y + 1, h - 1);
      out[std::size_t{y} * nw + x] =
          0.25f * (src[std::size_t{y0} * w + x0] + src[std::size_t{y0} * w + x1] +
                   src[std::size_t{y1} * w + x0] + src[std::size_t{y1} * w + x1]);
    }
  return out;
}

void append_level(const std::vector<glm::vec4>& level, std::uint32_t format,
                  std::vector<std::uint32_t>& out) {
  for (const glm::vec4& c : level) {
    switch (format) {
      case gpu::kTexelHalf:
        out.push_back(glm::packHalf2x16(glm::vec2(c.r, c.g)));
        out.push_back(glm::packHalf2x16(glm::vec2(c.b, c.a)));
        break;
      default:
        out.push_back(glm::packUnorm4x8(c));
        break;
    }
  }
}

std::string image_place(const Level& level, std::uint32_t index) {
  const ImageRef& ref = level.images[index];
  return ref.path.empty()
             ? fmt::format("{}: embedded image {} '{}'", level.source.string(), index, ref.name)
             : fmt::format("{}: image {} '{}' ({})", level.source.string(), index, ref.name,
                           ref.path.string());
}

}  // namespace

TextureSet TextureSet::build(const Level& level) {
  const auto start = std::chrono::steady_clock::now();
  TextureSet set;
  // (source, srgb) -> images_: an image is decoded once per colour space however many
  // ImageRefs name it (an asset placed several times imports its images each time). The source
  // is the file path, or the embedded bytes themselves.
  std::map<std::pair<std::string, bool>, std::uint32_t> image_of;
  auto image = [&](std::uint32_t index, bool srgb, const std::string& use) -> std::uint32_t {
    if (index >= level.images.size())
      throw InputError(fmt::format("{}: {} names image {} of {}", level.source.string(), use, index,
                                   level.images.size()));
    const ImageRef& ref = level.images[index];
    std::string source = ref.path.empty()
                             ? "data:" + std::string(ref.embedded.begin(), ref.embedded.end())
                             : "file:" + ref.path.string();
    if (auto it = image_of.find({source, srgb}); it != image_of.end()) return it->second;
    const std::string where = fmt::format("{} (used by {})", image_place(level, index), use);
    runtime::DecodedImage decoded =
        ref.path.empty()
            ? runtime::decode_image_bytes(ref.embedded, ref.mime_type, gpu::kMaxTextureSide, where)
            : runtime::decode_image_file(ref.path, gpu::kMaxTextureSide, where);
    TextureImage img;
    img.image = index;
    img.srgb = srgb;
    img.width = decoded.width;
    img.height = decoded.height;
    img.format = decoded.high_dynamic_range || srgb ? gpu::kTexelHalf : gpu::kTexelUnorm8;
    img.linear.resize(std::size_t{img.width} * img.height);
    for (std::size_t i = 0; i < img.linear.size(); ++i) {
      const float* p = &decoded.rgba[4 * i];
      glm::vec4 c(p[0], p[1], p[2], p[3]);
      if (srgb && !decoded.high_dynamic_range)
        c = glm::vec4(gpu::srgb_to_linear(c.r), gpu::srgb_to_linear(c.g), gpu::srgb_to_linear(c.b),
                      c.a);
      img.linear[i] = c;
    }
    img.first_word = static_cast<std::uint32_t>(set.texels_.size());
    std::vector<glm::vec4> level_texels = img.linear;
    std::uint32_t w = img.width, h = img.height;
    while (true) {
      append_level(level_texels, img.format, set.texels_);
      ++img.levels;
      if (set.texel_bytes() > gpu::kMaxTexelBytes)
        throw InputError(fmt::format("{}: the level's textures exceed {} MiB of texels", where,
                                     gpu::kMaxTexelBytes >> 20));
      if (w == 1 && h == 1) break;
      const std::uint32_t nw = std::max(w / 2, 1u), nh = std::max(h / 2, 1u);
      level_texels = downsample(level_texels, w, h, nw, nh);
      w = nw;
      h = nh;
    }
    img.bytes = (set.texels_.size() - img.first_word) * sizeof(std::uint32_t);
    set.images_.push_back(std::move(img));
    const auto id = static_cast<std::uint32_t>(set.images_.size() - 1);
    image_of[{std::move(source), srgb}] = id;
    return id;
  };
  auto record = [&](const TextureRef& t, bool srgb, const std::string& use) -> std::uint32_t {
    if (!t.present()) return gpu::kNoTexture;
    const std::uint32_t id = image(static_cast<std::uint32_t>(t.image), srgb, use);
    const TextureImage& img = set.images_[id];
    gpu::GpuTexture g{};
    g.size = glm::uvec4(img.width, img.height, img.levels, img.first_word);
    g.format = glm::uvec4(img.format, wrap_mode(t.sampler.wrap_s), wrap_mode(t.sampler.wrap_t),
                          filter_bits(t.sampler));
    // KHR_texture_transform: uv' = T(offset) R(rotation) S(scale) uv.
    const float c = std::cos(t.rotation), s = std::sin(t.rotation);
    g.transform_u =
        glm::vec4(c * t.scale.x, -s * t.scale.y, t.offset.x, static_cast<float>(t.texcoord));
    g.transform_v = glm::vec4(s * t.scale.x, c * t.scale.y, t.offset.y, 0.0f);
    set.records_.push_back(g);
    set.record_image_.push_back(id);
    return static_cast<std::uint32_t>(set.records_.size() - 1);
  };
  for (std::size_t m = 0; m < level.materials.size(); ++m) {
    const Material& mat = level.materials[m];
    auto use = [&](const char* slot) {
      return fmt::format("material {} '{}' {}", m, mat.name, slot);
    };
    glm::uvec4 slots;
    slots.x = record(mat.base_color_texture, true, use("baseColorTexture"));
    slots.y = record(mat.metallic_roughness_texture, false, use("metallicRoughnessTexture"));
    slots.z = record(mat.emissive_texture, true, use("emissiveTexture"));
    slots.w = record(mat.normal_texture, false, use("normalTexture"));
    set.material_.push_back(slots);
  }
  set.build_ms_ =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return set;
}

const TextureImage& TextureSet::image_of(std::uint32_t record) const {
  return images_.at(record_image_.at(record));
}

glm::vec4 TextureSet::sample(std::uint32_t record, glm::vec2 uv) const {
  const gpu::GpuTexture& t = records_.at(record);
  const TextureImage& img = image_of(record);
  const glm::vec2 st = gpu::texture_transform_uv(t, uv);
  const int w = static_cast<int>(img.width), h = static_cast<int>(img.height);
  auto texel = [&](int x, int y) {
    return img.linear[static_cast<std::size_t>(gpu::texture_wrap(y, h, t.format.z)) * img.width +
                      static_cast<std::size_t>(gpu::texture_wrap(x, w, t.format.y))];
  };
  if ((t.format.w & gpu::kFilterMagLinear) == 0u)
    return texel(static_cast<int>(std::floor(st.x * static_cast<float>(w))),
                 static_cast<int>(std::floor(st.y * static_cast<float>(h))));
  const glm::vec2 p = st * glm::vec2(static_cast<float>(w), static_cast<float>(h)) - 0.5f;
  const glm::vec2 i = glm::floor(p);
  const glm::vec2 f = p - i;
  const int x = static_cast<int>(i.x), y = static_cast<int>(i.y);
  return glm::mix(glm::mix(texel(x, y), texel(x + 1, y), f.x),
                  glm::mix(texel(x, y + 1), texel(x + 1, y + 1), f.x), f.y);
}

glm::vec3 integrate_texture_over_triangle(const TextureSet& set, std::uint32_t texture,
                                          glm::vec2 uv0, glm::vec2 uv1, glm::vec2 uv2) {
  const TextureImage& img = set.image_of(texture);
  const gpu::GpuTexture& t = set.records()[texture];
  const glm::vec2 a = gpu::texture_transform_uv(t, uv1) - gpu::texture_transform_uv(t, uv0);
  const glm::vec2 b = gpu::texture_transform_uv(t, uv2) - gpu::texture_transform_uv(t, uv0);
  const double texel_area =
      0.5 * std::abs(static_cast<double>(a.x) * b.y - static_cast<double>(a.y) * b.x) * img.width *
      img.height;
  // n x n sub-triangles: about four samples per covered texel, from 4 x 4 to 64 x 64.
  const int n = std::clamp(static_cast<int>(std::ceil(std::sqrt(4.0 * texel_area))), 4, 64);
  glm::dvec3 sum(0.0);
  const double inv = 1.0 / n;
  int count = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n - i; ++j) {
      // Upward sub-triangle (i, j) and, where it exists, the downward one beside it: centroids.
      for (int down = 0; down < (j < n - i - 1 ? 2 : 1); ++down) {
        const double b1 = (i + (down ? 2.0 : 1.0) / 3.0) * inv;
        const double b2 = (j + (down ? 2.0 : 1.0) / 3.0) * inv;
        const glm::vec2 uv = static_cast<float>(1.0 - b1 - b2) * uv0 +
                             static_cast<float>(b1) * uv1 + static_cast<float>(b2) * uv2;
        sum += glm::dvec3(glm::vec3(set.sample(texture, uv)));
        ++count;
      }
    }
  return glm::vec3(sum / static_cast<double>(count));
}

}  // namespace lantern::lighting
