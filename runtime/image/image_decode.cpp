// Image decoding through OpenImageIO (image_decode.h). Embedded bytes go through an in-memory
// IOProxy with a file name whose extension picks the reader (from the MIME type, else the
// signature), so nothing is written to disk.
#include "runtime/image/image_decode.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <vector>

#include "engine/core/error.h"

namespace lantern::runtime {
namespace {

bool is_ktx2(std::span<const std::uint8_t> b) {
  static constexpr std::uint8_t kSignature[12] = {0xab, 'K', 'T',  'X',  ' ',  '2',
                                                 '0',  0xbb, '\r', '\n', 0x1a, '\n'};
  return b.size() >= sizeof(kSignature) && std::memcmp(b.data(), kSignature, sizeof(kSignature)) == 0;
}

// KTX2 (glTF's image/ktx2, KHR_texture_basisu) decodes only where OpenImageIO has a reader for
// it; OpenImageIO 2.4 (Debian 12) has none, so such an image is one clear error up front rather
// than "no reader" from the depths of OpenImageIO.
void require_ktx2_reader(const std::string& where) {
  static const bool readable = [] {
    const bool found = OIIO::ImageInput::create("probe.ktx2", /*do_open=*/false) != nullptr;
    (void)OIIO::geterror();  // the probe's "no reader" must not linger as a global error
    return found;
  }();
  if (!readable)
    throw InputError(fmt::format(
        "{}: KTX2 image (image/ktx2, KHR_texture_basisu): this OpenImageIO ({}) has no KTX2 "
        "reader; convert the image to PNG, JPEG or EXR",
        where, OIIO_VERSION_STRING));
}

// The reader's file extension for encoded bytes: from the MIME type, else the signature.
std::string extension_for(std::span<const std::uint8_t> b, const std::string& mime,
                          const std::string& where) {
  if (mime == "image/png") return ".png";
  if (mime == "image/jpeg") return ".jpg";
  if (mime == "image/x-exr" || mime == "image/exr") return ".exr";
  if (mime == "image/ktx2" || is_ktx2(b)) {
    require_ktx2_reader(where);
    return ".ktx2";
  }
  auto starts = [&](std::initializer_list<std::uint8_t> sig) {
    return b.size() >= sig.size() && std::equal(sig.begin(), sig.end(), b.begin());
  };
  if (starts({0x89, 'P', 'N', 'G'})) return ".png";
  if (starts({0xff, 0xd8, 0xff})) return ".jpg";
  if (starts({0x76, 0x2f, 0x31, 0x01})) return ".exr";
  throw InputError(
      fmt::format("{}: embedded image is not PNG, JPEG or EXR (MIME type '{}', {} "
                  "bytes)",
                  where, mime, b.size()));
}

// OpenEXR 3.1 allocates every header attribute at the size the file claims before reading it
// (Imf::OpaqueAttribute::readValueFrom): a 60-byte file claiming a 1.7 GB attribute is a 1.7 GB
// allocation (found by scripts/fuzz.sh, tests/fuzz/regressions/image/). Walk the header first:
// every attribute (name\0 type\0 int32 size, value) must fit in the bytes the file has.
void check_exr_header(std::span<const std::uint8_t> b, const std::string& where) {
  if (b.size() < 8 || b[0] != 0x76 || b[1] != 0x2f || b[2] != 0x31 || b[3] != 0x01) return;
  const std::uint32_t flags = b[5] | (b[6] << 8) | (b[7] << 16);
  const bool multipart = (flags & 0x10) != 0;  // version bit 12
  // Names and types longer than OpenEXR's limit (31 chars, 255 with long names) would be parsed
  // differently by OpenEXR than here: refused, so an accepted header is read alike by both.
  const std::size_t max_name = (flags & 0x04) != 0 ? 255 : 31;  // version bit 10
  std::size_t at = 8;  // magic + version
  auto fail = [&](const std::string& what) {
    throw InputError(fmt::format("{}: malformed EXR header: {}", where, what));
  };
  auto c_string = [&]() {
    const std::size_t start = at;
    while (at < b.size() && b[at] != 0 && at - start <= max_name) ++at;
    if (at >= b.size() || b[at] != 0 || at - start > max_name)
      fail("an attribute name or type is unterminated or longer than OpenEXR allows");
    ++at;
    return std::string(reinterpret_cast<const char*>(b.data() + start), at - 1 - start);
  };
  for (int attributes = 0;; ++attributes) {
    if (at >= b.size()) fail("no end of header");
    if (b[at] == 0) {  // end of one header; a multi-part file ends its list with an empty one
      ++at;
      if (!multipart || (at < b.size() && b[at] == 0)) return;
      continue;
    }
    if (attributes > 4096) fail("more than 4096 attributes");
    const std::string name = c_string();
    c_string();  // type
    if (at + 4 > b.size()) fail(fmt::format("attribute '{}' has no size", name));
    std::int32_t size = 0;
    std::memcpy(&size, b.data() + at, 4);  // little-endian, as the format and this machine
    at += 4;
    if (size < 0 || static_cast<std::size_t>(size) > b.size() - at)
      fail(fmt::format("attribute '{}' claims {} bytes, {} remain in the file", name, size,
                       b.size() - at));
    at += static_cast<std::size_t>(size);
  }
}

// glTF colour and alpha are straight (unassociated): OpenImageIO would premultiply PNG colour by
// alpha on read.
OIIO::ImageSpec straight_alpha() {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  return config;
}

DecodedImage read_all(OIIO::ImageInput& in, std::uint32_t max_side, const std::string& where) {
  const OIIO::ImageSpec& spec = in.spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.depth > 1)
    throw InputError(fmt::format("{}: image has no 2D pixels ({}x{}x{}, {} channels)", where,
                                 spec.width, spec.height, spec.depth, spec.nchannels));
  if (static_cast<std::uint32_t>(spec.width) > max_side ||
      static_cast<std::uint32_t>(spec.height) > max_side)
    throw InputError(fmt::format("{}: image is {}x{}, larger than the {}x{} texture limit", where,
                                 spec.width, spec.height, max_side, max_side));
  const int channels = std::min(spec.nchannels, 4);
  DecodedImage out;
  out.width = static_cast<std::uint32_t>(spec.width);
  out.height = static_cast<std::uint32_t>(spec.height);
  const OIIO::TypeDesc::BASETYPE base = static_cast<OIIO::TypeDesc::BASETYPE>(spec.format.basetype);
  out.high_dynamic_range = base == OIIO::TypeDesc::FLOAT || base == OIIO::TypeDesc::HALF ||
                           base == OIIO::TypeDesc::DOUBLE;
  const std::size_t texels = std::size_t{out.width} * out.height;
  std::vector<float> raw(texels * static_cast<std::size_t>(channels));
  if (!in.read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, raw.data()))
    throw InputError(fmt::format("{}: cannot decode image: {}", where, in.geterror()));
  out.rgba.resize(4 * texels);
  for (std::size_t i = 0; i < texels; ++i) {
    const float* p = &raw[i * static_cast<std::size_t>(channels)];
    float* q = &out.rgba[4 * i];
    const bool grey = channels < 3;
    q[0] = p[0];
    q[1] = grey ? p[0] : p[1];
    q[2] = grey ? p[0] : p[2];
    q[3] = channels == 4 ? p[3] : (channels == 2 ? p[1] : 1.0f);
  }
  for (float v : out.rgba)
    if (!std::isfinite(v))
      throw InputError(fmt::format("{}: image holds NaN or infinite values", where));
  return out;
}

}  // namespace

DecodedImage decode_image_file(const std::filesystem::path& path, std::uint32_t max_side,
                               const std::string& where) {
  if (!std::filesystem::is_regular_file(path))
    throw InputError(fmt::format("{}: image file {} not found", where, path.string()));
  {
    std::ifstream file(path, std::ios::binary);
    char magic[4] = {};
    file.read(magic, 4);
    if (file && std::memcmp(magic, "\x76\x2f\x31\x01", 4) == 0) {  // EXR: check its header
      file.seekg(0);
      const std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(file),
                                            std::istreambuf_iterator<char>()};
      check_exr_header(bytes, fmt::format("{} ({})", where, path.string()));
    }
    std::uint8_t head[12] = {};
    file.clear();
    file.seekg(0);
    file.read(reinterpret_cast<char*>(head), sizeof(head));
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (is_ktx2(head) || extension == ".ktx2")
      require_ktx2_reader(fmt::format("{} ({})", where, path.string()));
  }
  const OIIO::ImageSpec config = straight_alpha();
  auto in = OIIO::ImageInput::open(path.string(), &config);
  if (!in)
    throw InputError(
        fmt::format("{}: cannot read image {}: {}", where, path.string(), OIIO::geterror()));
  return read_all(*in, max_side, where);
}

DecodedImage decode_image_bytes(std::span<const std::uint8_t> bytes, const std::string& mime_type,
                                std::uint32_t max_side, const std::string& where) {
  if (bytes.empty()) throw InputError(fmt::format("{}: embedded image has no bytes", where));
  check_exr_header(bytes, where);
  const std::string name = "embedded" + extension_for(bytes, mime_type, where);
  OIIO::Filesystem::IOMemReader proxy(bytes.data(), bytes.size());
  const OIIO::ImageSpec config = straight_alpha();
  auto in = OIIO::ImageInput::create(name, /*do_open=*/true, &config, &proxy);
  if (!in)
    throw InputError(fmt::format("{}: cannot read embedded image ({} bytes): {}", where,
                                 bytes.size(), OIIO::geterror()));
  return read_all(*in, max_side, where);
}

}  // namespace lantern::runtime
