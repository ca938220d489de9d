// Test harness: a FrameRenderer (baseline) with a HeadlessTarget, rendering one snapshot per call
// through the frame session and reading the linear HDR image back.
#pragma once

#include <memory>

#include "engine/world/frame_snapshot.h"
#include "lighting/frame/frame_renderer.h"
#include "lighting/frame/frame_session.h"
#include "lighting/integrators/integrator_registry.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/target/headless_target.h"

namespace lantern::test {

class FrameHarness {
 public:
  FrameHarness(runtime::Device& device, runtime::ShaderLibrary& shaders,
               std::shared_ptr<const Level> level, std::uint32_t width, std::uint32_t height)
      : renderer_(device, shaders, level,
                  lighting::make_integrator(device, shaders,
                                            {.name = "baseline"}),
                  width, height, 1),
        target_(device, {.width = width, .height = height}),
        session_(device, target_, renderer_) {
    renderer_.warm_up();
  }

  runtime::ImageRGBA32F render(const FrameSnapshot& snapshot) {
    session_.render(snapshot);
    return target_.read_output();
  }
  // The last frame's output (after rendering through session() directly).
  runtime::ImageRGBA32F output() { return target_.read_output(); }

  lighting::FrameRenderer& renderer() { return renderer_; }
  lighting::FrameSession& session() { return session_; }

 private:
  lighting::FrameRenderer renderer_;
  runtime::HeadlessTarget target_;
  lighting::FrameSession session_;
};

}  // namespace lantern::test
