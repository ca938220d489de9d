// Parsing of flag values shared by several commands.
#include <fmt/format.h>

#include <charconv>

#include "apps/lantern/commands.h"
#include "engine/core/error.h"

namespace lantern::app {
namespace {

std::uint32_t parse_dimension(std::string_view text, std::string_view size) {
  std::uint32_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || value == 0 || value > 16384)
    throw InputError(fmt::format("--size {}: expected WxH with W and H in 1..16384", size));
  return value;
}

}  // namespace

std::pair<std::uint32_t, std::uint32_t> parse_size(std::string_view size) {
  const std::size_t x = size.find('x');
  if (x == std::string_view::npos)
    throw InputError(fmt::format("--size {}: expected WxH, e.g. 640x360", size));
  return {parse_dimension(size.substr(0, x), size), parse_dimension(size.substr(x + 1), size)};
}

}  // namespace lantern::app
