// What a frame's passes declared: resources (transient, imported, history) and, per pass, the
// uses of each resource version. Pure data, filled by RenderGraph/PassBuilder, read by the
// compiler; no Vulkan objects are created from it here.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "runtime/graph/handles.h"
#include "runtime/graph/resource_desc.h"

namespace lantern::runtime::graph {

class PassContext;

enum class Origin : uint8_t {
  Transient,        // created and owned by the graph for this frame
  Imported,         // owned outside (swapchain image, light buffers); state given at import
  History,          // this frame's version of a persistent resource kept for the next frame
  HistoryPrevious,  // last frame's version of a History resource, read-only
};
[[nodiscard]] const char* origin_name(Origin origin);

struct ImportInfo {
  bool read_only = false;            // writes from passes are rejected at compile time
  AccessState initial{};             // how the resource was last used before this frame
  std::optional<AccessState> final;  // how it must be left (e.g. PRESENT_SRC, host read)
};

struct ResourceDecl {
  std::string name;
  bool is_image = false;
  BufferDesc buffer;
  ImageDesc image;
  Origin origin = Origin::Transient;
  ImportInfo import;              // Imported and History* (initial = last frame's final state)
  uint32_t history_slot = 0;      // History*: physical slot of the persistent pair
  uint32_t latest_version = 0;    // versions 1..latest were produced by writes
  std::vector<uint32_t> writers;  // writers[v-1] = pass producing version v
  VkBufferUsageFlags buffer_usage = 0;  // accumulated from declared uses
  VkImageUsageFlags image_usage = 0;
  VkBuffer imported_buffer = VK_NULL_HANDLE;
  VkImage imported_image = VK_NULL_HANDLE;
  VkImageView imported_view = VK_NULL_HANDLE;

  // Version 0 holds meaningful contents (imported data, last frame's history).
  [[nodiscard]] bool has_initial_contents() const {
    return origin == Origin::Imported || origin == Origin::HistoryPrevious;
  }
};

struct ResourceUse {
  uint32_t resource = kInvalidIndex;
  uint32_t version = 0;  // version read, or version overwritten by a write
  Access access = Access::StorageRead;
};

struct PassDecl {
  std::string name;  // module.stage, e.g. "restir.temporal"
  PassKind kind = PassKind::Compute;
  bool side_effect = false;  // never culled
  std::vector<ResourceUse> uses;
  std::function<void(PassContext&)> execute;
};

struct GraphDecl {
  std::vector<PassDecl> passes;
  std::vector<ResourceDecl> resources;
  std::vector<std::string> errors;  // misuse found while declaring; reported by bake()
};

}  // namespace lantern::runtime::graph
