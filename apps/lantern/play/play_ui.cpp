// PlayUi: ImGui context + Lantern's ImGui renderer through the render graph (play_ui.h).
#include "apps/lantern/play/play_ui.h"

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cstring>

#include "apps/lantern/play/play_input.h"
#include "play/play_ui.h"
#include "runtime/core/device.h"
#include "runtime/gpu/bindings.h"
#include "runtime/gpu/shader_library.h"

namespace lantern::app {
namespace {

constexpr VkFormat kUiFormat = VK_FORMAT_R16G16B16A16_SFLOAT;

runtime::Buffer host_buffer(runtime::Device& device, VkDeviceSize bytes, const char* name) {
  return runtime::Buffer(device, {.size = std::max<VkDeviceSize>(bytes, 256),
                                  .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                  .memory = runtime::MemoryUsage::Upload,
                                  .name = name});
}

// Grows `buffer` to at least `bytes` (the slot's previous frame has completed).
void ensure(runtime::Device& device, runtime::Buffer& buffer, VkDeviceSize bytes,
            const char* name) {
  if (buffer && buffer.size() >= bytes) return;
  buffer = host_buffer(device, std::max<VkDeviceSize>(bytes * 3 / 2, 64 * 1024), name);
}

}  // namespace

PlayUi::PlayUi(runtime::Device& device, runtime::ShaderLibrary& shaders, std::uint32_t slots)
    : device_(device),
      context_(ImGui::CreateContext()),
      draw_(device, shaders.load("play/play_ui.vert"), shaders.load("play/play_ui.frag"),
            {.name = "play.ui",
             .color_formats = {kUiFormat},
             .cull_mode = VK_CULL_MODE_NONE,
             .depth_test = false,
             .depth_write = false,
             .alpha_blend = true}),
      composite_(device, shaders.load("play/play_ui_composite.comp"),
                 {.name = "play.ui_composite"}),
      vertices_(slots),
      indices_(slots) {
  ImGui::SetCurrentContext(context_);
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini next to the user's files
  io.LogFilename = nullptr;
  ImGui::StyleColorsDark();
  ImGui::GetStyle().WindowRounding = 0.0f;
  unsigned char* pixels = nullptr;
  int w = 0;
  int h = 0;
  io.Fonts->GetTexDataAsAlpha8(&pixels, &w, &h);
  font_width_ = static_cast<std::uint32_t>(w);
  font_height_ = static_cast<std::uint32_t>(h);
  const std::size_t bytes = std::size_t{font_width_} * font_height_;
  font_ = host_buffer(device, (bytes + 3) / 4 * 4, "play.ui_font");
  std::memset(font_.mapped(), 0, font_.size());
  std::memcpy(font_.mapped(), pixels, bytes);
  io.Fonts->SetTexID(nullptr);
  io.Fonts->ClearTexData();
}

PlayUi::~PlayUi() {
  if (context_ != nullptr) ImGui::DestroyContext(context_);
}

void PlayUi::warm_up() {
  composite_.warm_up();
  // The graphics pipeline is compiled by the driver on first use (small).
}

void PlayUi::new_frame(const PlayInput& input, std::uint32_t width, std::uint32_t height,
                       float dt) {
  ImGui::SetCurrentContext(context_);
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(static_cast<float>(width), static_cast<float>(height));
  io.DeltaTime = dt > 0.0f ? dt : 1.0f / 60.0f;
  io.MousePos = ImVec2(static_cast<float>(input.cursor_x), static_cast<float>(input.cursor_y));
  io.MouseDown[0] = input.button(GLFW_MOUSE_BUTTON_LEFT);
  io.MouseDown[1] = input.button(GLFW_MOUSE_BUTTON_RIGHT);
  io.MouseDown[2] = input.button(GLFW_MOUSE_BUTTON_MIDDLE);
  io.MouseWheel = static_cast<float>(input.scroll_y);
  io.KeyShift = input.key(GLFW_KEY_LEFT_SHIFT) || input.key(GLFW_KEY_RIGHT_SHIFT);
  io.KeyCtrl = input.key(GLFW_KEY_LEFT_CONTROL) || input.key(GLFW_KEY_RIGHT_CONTROL);
  ImGui::NewFrame();
  frame_open_ = true;
}

bool PlayUi::wants_mouse() const {
  return frame_open_ && ImGui::GetIO().WantCaptureMouse;
}
bool PlayUi::wants_keyboard() const {
  return frame_open_ && ImGui::GetIO().WantCaptureKeyboard;
}

void PlayUi::end_frame_without_drawing() {
  if (!frame_open_) return;
  ImGui::SetCurrentContext(context_);
  ImGui::EndFrame();
  frame_open_ = false;
  last_triangles_ = 0;
}

runtime::graph::ImageHandle PlayUi::add_passes(runtime::graph::RenderGraph& graph,
                                               runtime::graph::ImageHandle target,
                                               std::uint32_t width, std::uint32_t height,
                                               std::uint32_t slot) {
  namespace graph_ns = runtime::graph;
  ImGui::SetCurrentContext(context_);
  ImGui::Render();
  frame_open_ = false;
  const ImDrawData* data = ImGui::GetDrawData();
  last_triangles_ = 0;
  if (data == nullptr || data->TotalVtxCount == 0) return target;

  // Vertices (5 words each, ImDrawVert as is) and 32-bit indices of every list, in order.
  static_assert(sizeof(ImDrawVert) == 20, "play_ui.vert reads 5 words per vertex");
  runtime::Buffer& vbuf = vertices_.at(slot);
  runtime::Buffer& ibuf = indices_.at(slot);
  ensure(device_, vbuf, std::size_t(data->TotalVtxCount) * sizeof(ImDrawVert), "play.ui_vertices");
  ensure(device_, ibuf, std::size_t(data->TotalIdxCount) * sizeof(std::uint32_t),
         "play.ui_indices");
  struct Draw {
    gpu::PlayUiPush push;
    VkRect2D scissor;
    std::uint32_t count;
  };
  std::vector<Draw> draws;
  auto* vdst = reinterpret_cast<ImDrawVert*>(vbuf.mapped());
  auto* idst = reinterpret_cast<std::uint32_t*>(ibuf.mapped());
  std::uint32_t vbase = 0;
  std::uint32_t ibase = 0;
  const float sx = 2.0f / data->DisplaySize.x;
  const float sy = 2.0f / data->DisplaySize.y;
  const gpu::vec4 st(sx, sy, -1.0f - data->DisplayPos.x * sx, -1.0f - data->DisplayPos.y * sy);
  for (int l = 0; l < data->CmdListsCount; ++l) {
    const ImDrawList* list = data->CmdLists[l];
    std::memcpy(vdst + vbase, list->VtxBuffer.Data,
                std::size_t(list->VtxBuffer.Size) * sizeof(ImDrawVert));
    for (int i = 0; i < list->IdxBuffer.Size; ++i) idst[ibase + i] = list->IdxBuffer.Data[i];
    for (int c = 0; c < list->CmdBuffer.Size; ++c) {
      const ImDrawCmd& cmd = list->CmdBuffer.Data[c];
      if (cmd.UserCallback != nullptr || cmd.ElemCount == 0) continue;
      const float x0 = std::clamp(cmd.ClipRect.x - data->DisplayPos.x, 0.0f, float(width));
      const float y0 = std::clamp(cmd.ClipRect.y - data->DisplayPos.y, 0.0f, float(height));
      const float x1 = std::clamp(cmd.ClipRect.z - data->DisplayPos.x, 0.0f, float(width));
      const float y1 = std::clamp(cmd.ClipRect.w - data->DisplayPos.y, 0.0f, float(height));
      if (x1 <= x0 || y1 <= y0) continue;
      Draw d{};
      d.push.scale_translate = st;
      d.push.vertex_offset = vbase + cmd.VtxOffset;
      d.push.index_offset = ibase + cmd.IdxOffset;
      d.push.font_width = font_width_;
      d.push.font_height = font_height_;
      d.scissor = {{static_cast<std::int32_t>(x0), static_cast<std::int32_t>(y0)},
                   {static_cast<std::uint32_t>(x1 - std::floor(x0)),
                    static_cast<std::uint32_t>(y1 - std::floor(y0))}};
      d.count = cmd.ElemCount;
      last_triangles_ += cmd.ElemCount / 3;
      draws.push_back(d);
    }
    vbase += static_cast<std::uint32_t>(list->VtxBuffer.Size);
    ibase += static_cast<std::uint32_t>(list->IdxBuffer.Size);
  }
  if (draws.empty()) return target;

  const graph_ns::BufferHandle vhandle =
      graph.import_buffer("play.ui_vertices", vbuf.handle(), {vbuf.size()}, {.read_only = true});
  const graph_ns::BufferHandle ihandle =
      graph.import_buffer("play.ui_indices", ibuf.handle(), {ibuf.size()}, {.read_only = true});
  const graph_ns::BufferHandle fhandle =
      graph.import_buffer("play.ui_font", font_.handle(), {font_.size()}, {.read_only = true});
  const graph_ns::ImageHandle layer =
      graph.create_image("play.ui_layer", {.extent = {width, height, 1}, .format = kUiFormat});

  struct DrawData {
    graph_ns::BufferHandle vertices, indices, font;
    graph_ns::ImageHandle layer;
  };
  const DrawData& drawn = graph.add_pass<DrawData>(
      "play.ui", graph_ns::PassKind::Graphics,
      [&](graph_ns::PassBuilder& b, DrawData& d) {
        d.vertices = vhandle;
        d.indices = ihandle;
        d.font = fhandle;
        b.read(vhandle, graph_ns::Access::StorageRead);
        b.read(ihandle, graph_ns::Access::StorageRead);
        b.read(fhandle, graph_ns::Access::StorageRead);
        d.layer = b.write(layer, graph_ns::Access::ColorAttachment);
      },
      [this, draws = std::move(draws), width, height](graph_ns::PassContext& ctx,
                                                      const DrawData& d) {
        const runtime::ColorTarget color{.view = ctx.view(d.layer),
                                         .clear = VkClearColorValue{{0.0f, 0.0f, 0.0f, 0.0f}}};
        runtime::begin_rendering(device_, ctx.cmd(), {width, height}, {&color, 1});
        draw_.bind(ctx.cmd(), runtime::Bindings(draw_)
                                  .buffer("ui_vertices", ctx.buffer(d.vertices), 0, VK_WHOLE_SIZE)
                                  .buffer("ui_indices", ctx.buffer(d.indices), 0, VK_WHOLE_SIZE)
                                  .buffer("ui_font", ctx.buffer(d.font), 0, VK_WHOLE_SIZE));
        for (const Draw& draw : draws) {
          vkCmdSetScissor(ctx.cmd(), 0, 1, &draw.scissor);
          draw_.push_constants(ctx.cmd(), draw.push);
          vkCmdDraw(ctx.cmd(), draw.count, 1, 0, 0);
        }
        runtime::end_rendering(device_, ctx.cmd());
      });

  struct CompositeData {
    graph_ns::ImageHandle layer, target;
  };
  const gpu::PlayCompositePush push{width, height, 0u, 0u};
  const CompositeData& composited = graph.add_pass<CompositeData>(
      "play.ui_composite", graph_ns::PassKind::Compute,
      [&](graph_ns::PassBuilder& b, CompositeData& d) {
        d.layer = drawn.layer;
        b.read(drawn.layer, graph_ns::Access::StorageRead);
        d.target = b.write(target, graph_ns::Access::StorageReadWrite);
      },
      [this, push](graph_ns::PassContext& ctx, const CompositeData& d) {
        composite_.bind(ctx.cmd(),
                        runtime::Bindings(composite_)
                            .image_view("ui_layer", ctx.view(d.layer), VK_IMAGE_LAYOUT_GENERAL)
                            .image_view("target", ctx.view(d.target), VK_IMAGE_LAYOUT_GENERAL));
        composite_.push_constants(ctx.cmd(), push);
        composite_.dispatch_threads(ctx.cmd(), push.width, push.height);
      });
  return composited.target;
}

}  // namespace lantern::app
