// How the G-buffer is produced (lighting/gbuffer/gbuffer_pass.h has the passes; the images and
// encodings are the same whichever runs), and its frame setting `--set gbuffer=METHOD`.
#pragma once

#include <cstdint>
#include <string_view>

namespace lantern::lighting {

enum class GBufferMethod : std::uint8_t {
  // Per frame: Forward when the frame has at most one triangle per kForwardPixelsPerTriangle
  // pixels, Host when it has at least kHostTrianglesPerPixel triangles per pixel and the scene
  // has host visibility (a CPU device), else Visibility (gbuffer_pass.h).
  Auto,
  // Cull, raster the kept triangles' ids into gbuffer.visibility, resolve every image per pixel:
  // cost ~ triangles / cores + pixels. 4-5x faster than Forward on night_market at 320x180.
  Visibility,
  // One raster pass interpolating every attribute: cost ~ triangles (single-threaded front end,
  // every varying) + pixels (cheaper per pixel than the resolve: 1.8x faster on cornell_lights).
  Forward,
  // Embree traces the camera rays on the host, resolve as Visibility: cost ~ pixels x log
  // triangles. Needs the scene's HostVisibility (GpuScene::host_visibility()), and traces every
  // instance of it.
  Host,
};

// "auto", "visibility", "forward", "host"; InputError naming the value otherwise.
GBufferMethod parse_gbuffer_method(std::string_view value);
std::string_view gbuffer_method_name(GBufferMethod method);

}  // namespace lantern::lighting
