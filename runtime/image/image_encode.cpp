// In-memory image encoding through OpenImageIO (image_encode.h).
#include "runtime/image/image_encode.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include "engine/core/error.h"

namespace lantern::runtime {
namespace {

std::vector<std::uint8_t> encode(std::uint32_t width, std::uint32_t height, int channels,
                                 OIIO::TypeDesc stored, OIIO::TypeDesc given, const void* pixels,
                                 const std::string& extension) {
  const std::string name = "image" + extension;
  OIIO::Filesystem::IOVecOutput proxy;
  auto out = OIIO::ImageOutput::create(name);
  if (!out) throw RuntimeError(fmt::format("encode {}: {}", extension, OIIO::geterror()));
  OIIO::ImageSpec spec(static_cast<int>(width), static_cast<int>(height), channels, stored);
  spec.attribute("oiio:UnassociatedAlpha", 1);  // texture content: straight alpha, as given
  if (!out->set_ioproxy(&proxy) || !out->open(name, spec) || !out->write_image(given, pixels) ||
      !out->close())
    throw RuntimeError(fmt::format("encode {}: {}", extension, out->geterror()));
  return {proxy.buffer().begin(), proxy.buffer().end()};
}

}  // namespace

std::vector<std::uint8_t> encode_rgba8(std::uint32_t width, std::uint32_t height,
                                       std::span<const std::uint8_t> rgba8,
                                       const std::string& extension) {
  if (rgba8.size() != 4ull * width * height)
    throw RuntimeError(
        fmt::format("encode_rgba8: {} bytes for {}x{}", rgba8.size(), width, height));
  if (extension == ".jpg" || extension == ".jpeg") {  // JPEG has no alpha
    std::vector<std::uint8_t> rgb;
    rgb.reserve(3ull * width * height);
    for (std::size_t i = 0; i < rgba8.size(); i += 4)
      rgb.insert(rgb.end(), &rgba8[i], &rgba8[i] + 3);
    return encode(width, height, 3, OIIO::TypeDesc::UINT8, OIIO::TypeDesc::UINT8, rgb.data(),
                  extension);
  }
  return encode(width, height, 4, OIIO::TypeDesc::UINT8, OIIO::TypeDesc::UINT8, rgba8.data(),
                extension);
}

std::vector<std::uint8_t> encode_exr(std::uint32_t width, std::uint32_t height,
                                     std::span<const float> rgba) {
  if (rgba.size() != 4ull * width * height)
    throw RuntimeError(fmt::format("encode_exr: {} floats for {}x{}", rgba.size(), width, height));
  return encode(width, height, 4, OIIO::TypeDesc::HALF, OIIO::TypeDesc::FLOAT, rgba.data(), ".exr");
}

}  // namespace lantern::runtime
