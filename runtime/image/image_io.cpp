#include "runtime/image/image_io.h"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <system_error>

#include "engine/core/error.h"
#include "shared/tonemap.h"

namespace lantern::runtime {
namespace fs = std::filesystem;

std::size_t ImageRGBA32F::count_non_finite() const {
  std::size_t bad = 0;
  for (std::size_t i = 0; i < pixels.size(); i += 4)
    if (!std::isfinite(pixels[i]) || !std::isfinite(pixels[i + 1]) || !std::isfinite(pixels[i + 2]))
      ++bad;
  return bad;
}

ImageFormat image_format_for(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".exr") return ImageFormat::Exr;
  if (ext == ".png") return ImageFormat::Png;
  throw InputError(fmt::format("{}: unsupported image extension '{}' (use .exr or .png)",
                               path.string(), ext));
}

namespace {

// Writes `pixels` (channels per pixel, given type) to a temporary file beside `path`, then renames.
// An empty "DateTime" keeps OpenImageIO from stamping the write time into the file, so the same
// pixels always give the same bytes (deterministic captures compare files bitwise).
void write_atomic(const fs::path& path, OIIO::ImageSpec spec, OIIO::TypeDesc type,
                  const void* pixels) {
  spec.attribute("DateTime", "");
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  if (!fs::is_directory(dir))
    throw InputError(fmt::format("{}: directory '{}' does not exist", path.string(), dir.string()));
  if (fs::is_directory(path))
    throw InputError(fmt::format("{}: is a directory, not an image file", path.string()));
  auto out = OIIO::ImageOutput::create(path.string());
  if (!out) throw RuntimeError(fmt::format("{}: {}", path.string(), OIIO::geterror()));
  const fs::path temp = dir / fmt::format(".{}.{}.partial", path.filename().string(), getpid());
  if (!out->open(temp.string(), spec) || !out->write_image(type, pixels) || !out->close()) {
    const std::string why = out->geterror();
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw RuntimeError(fmt::format("{}: could not write image: {}", path.string(), why));
  }
  std::error_code ec;
  fs::rename(temp, path, ec);
  if (ec) {
    std::error_code ignored;  // keep `ec`: it is the reason the user sees
    fs::remove(temp, ignored);
    throw RuntimeError(fmt::format("{}: could not move image into place: {}", path.string(),
                                   ec.message()));
  }
}

void require_finite(const fs::path& path, const ImageRGBA32F& image) {
  if (image.width == 0 || image.height == 0 ||
      image.pixels.size() != 4ull * image.width * image.height)
    throw RuntimeError(fmt::format("{}: image has inconsistent size {}x{} ({} floats)",
                                   path.string(), image.width, image.height, image.pixels.size()));
  if (const std::size_t bad = image.count_non_finite())
    throw RuntimeError(fmt::format("{}: refusing to write an image with {} NaN/Inf pixels",
                                   path.string(), bad));
}

}  // namespace

void write_exr(const fs::path& path, const ImageRGBA32F& image) {
  require_finite(path, image);
  std::vector<float> rgb(3ull * image.width * image.height);
  for (std::size_t i = 0, n = rgb.size() / 3; i < n; ++i)
    for (int c = 0; c < 3; ++c) rgb[3 * i + c] = image.pixels[4 * i + c];
  OIIO::ImageSpec spec(static_cast<int>(image.width), static_cast<int>(image.height), 3,
                       OIIO::TypeDesc::FLOAT);
  spec.attribute("compression", "zip");
  write_atomic(path, spec, OIIO::TypeDesc::FLOAT, rgb.data());
}

void write_png(const fs::path& path, const ImageRGBA32F& image, float exposure) {
  require_finite(path, image);
  std::vector<std::uint8_t> rgb(3ull * image.width * image.height);
  for (std::size_t i = 0, n = rgb.size() / 3; i < n; ++i) {
    const gpu::vec3 radiance(image.pixels[4 * i], image.pixels[4 * i + 1], image.pixels[4 * i + 2]);
    const gpu::vec3 srgb = gpu::tonemap_to_srgb(radiance, exposure);
    for (int c = 0; c < 3; ++c)
      rgb[3 * i + c] = static_cast<std::uint8_t>(std::lround(srgb[c] * 255.0f));
  }
  OIIO::ImageSpec spec(static_cast<int>(image.width), static_cast<int>(image.height), 3,
                       OIIO::TypeDesc::UINT8);
  write_atomic(path, spec, OIIO::TypeDesc::UINT8, rgb.data());
}

void write_image(const fs::path& path, const ImageRGBA32F& image, float exposure) {
  if (image_format_for(path) == ImageFormat::Exr)
    write_exr(path, image);
  else
    write_png(path, image, exposure);
}

ImageRGBA32F read_image(const fs::path& path) {
  if (!fs::exists(path)) throw InputError(fmt::format("{}: no such image file", path.string()));
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) throw InputError(fmt::format("{}: cannot read image: {}", path.string(), OIIO::geterror()));
  const OIIO::ImageSpec& spec = in->spec();
  const int channels = spec.nchannels;
  if (spec.width <= 0 || spec.height <= 0 || channels <= 0)
    throw InputError(fmt::format("{}: image has no pixels", path.string()));
  std::vector<float> raw(static_cast<std::size_t>(spec.width) * spec.height * channels);
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, raw.data()))
    throw InputError(fmt::format("{}: cannot read image: {}", path.string(), in->geterror()));
  ImageRGBA32F image(static_cast<std::uint32_t>(spec.width), static_cast<std::uint32_t>(spec.height));
  for (std::size_t i = 0, n = static_cast<std::size_t>(spec.width) * spec.height; i < n; ++i) {
    const float* p = &raw[i * channels];
    float* q = &image.pixels[4 * i];
    q[0] = p[0];
    q[1] = channels >= 3 ? p[1] : p[0];
    q[2] = channels >= 3 ? p[2] : p[0];
    q[3] = channels == 4 ? p[3] : (channels == 2 ? p[1] : 1.0f);
  }
  return image;
}

}  // namespace lantern::runtime
