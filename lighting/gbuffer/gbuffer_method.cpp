// G-buffer method names (gbuffer_method.h).
#include "lighting/gbuffer/gbuffer_method.h"

#include <fmt/format.h>

#include "engine/core/error.h"

namespace lantern::lighting {

GBufferMethod parse_gbuffer_method(std::string_view value) {
  if (value == "auto") return GBufferMethod::Auto;
  if (value == "visibility") return GBufferMethod::Visibility;
  if (value == "forward") return GBufferMethod::Forward;
  if (value == "host") return GBufferMethod::Host;
  throw InputError(
      fmt::format("--set gbuffer={}: expected auto, visibility, forward or host", value));
}

std::string_view gbuffer_method_name(GBufferMethod method) {
  switch (method) {
    case GBufferMethod::Auto:
      return "auto";
    case GBufferMethod::Visibility:
      return "visibility";
    case GBufferMethod::Forward:
      return "forward";
    case GBufferMethod::Host:
      return "host";
  }
  return "?";
}

}  // namespace lantern::lighting
