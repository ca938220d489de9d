// Typed, versioned handles to render-graph resources. A handle names one version of one resource;
// every write returns the next version, so "who produced what I read" is explicit in the types.
#pragma once

#include <cstdint>
#include <limits>

namespace lantern::runtime::graph {

inline constexpr uint32_t kInvalidIndex = std::numeric_limits<uint32_t>::max();

template <class Tag>
struct ResourceHandle {
  uint32_t index = kInvalidIndex;  // resource slot in the graph of this frame
  uint32_t version = 0;            // 0 = contents on entry (undefined for transients)

  [[nodiscard]] bool valid() const { return index != kInvalidIndex; }
  explicit operator bool() const { return valid(); }
  friend bool operator==(const ResourceHandle&, const ResourceHandle&) = default;
};

using BufferHandle = ResourceHandle<struct BufferTag>;
using ImageHandle = ResourceHandle<struct ImageTag>;

}  // namespace lantern::runtime::graph
