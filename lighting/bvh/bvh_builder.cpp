// Binned-SAH BVH build: each node bins primitive centroids along the three axes, picks the plane
// of least SAH cost, and partitions its primitive range in place. Subtrees above a size threshold
// are built on other threads into their own node arrays, then spliced in depth-first order, so the
// result does not depend on which thread built what.
#include "lighting/bvh/bvh_builder.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <future>
#include <thread>

#include "engine/core/error.h"

namespace lantern::lighting {
namespace {

constexpr std::uint32_t kMaxBins = 32;
// Below this depth nodes split by SAH; deeper ones split at the centroid median, which halves the
// range each level, so trees stay shallower than gpu::kBvhStackSize for any realistic input.
constexpr std::uint32_t kMedianSplitDepth = gpu::kBvhStackSize - 24;
// SAH constants: cost of visiting a node relative to intersecting one primitive.
constexpr float kTraversalCost = 1.0f;
constexpr float kIntersectionCost = 1.0f;

// Node boxes are padded outward by a few ulps plus a tiny absolute amount: a ray lying exactly in
// a box's boundary plane with a zero direction component (an axis-aligned ray along a mesh edge)
// then sits strictly inside that slab, and the 1-ulp difference between v0 + e1 and v1 in the
// stored triangles can never put a hit outside its leaf box.
constexpr float kPadRelative = 1.0f / (1 << 21);
constexpr float kPadAbsolute = 1e-20f;

Aabb padded(const Aabb& box) {
  Aabb out;
  out.min = box.min - (glm::abs(box.min) * kPadRelative + kPadAbsolute);
  out.max = box.max + (glm::abs(box.max) * kPadRelative + kPadAbsolute);
  return out;
}

gpu::BvhNode make_node(const Aabb& box, std::uint32_t index, std::uint32_t count) {
  const Aabb p = padded(box);
  gpu::BvhNode node;
  node.bounds_min = glm::vec4(p.min, glm::uintBitsToFloat(index));
  node.bounds_max = glm::vec4(p.max, glm::uintBitsToFloat(count));
  return node;
}

struct Split {
  int axis = -1;          // -1: no usable plane (all centroids coincide)
  std::uint32_t bin = 0;  // primitives in bins [0, bin) go left
  float cost = std::numeric_limits<float>::max();
};

// One primitive as the build moves it around: box, centroid and input index in one 48-byte record,
// so binning and partitioning stream through memory instead of chasing indices.
struct PrimRef {
  Aabb box;
  glm::vec3 centroid;
  std::uint32_t id;
};

class Builder {
 public:
  Builder(std::span<const Aabb> bounds, const BvhBuildOptions& options)
      : options_(options), refs_(bounds.size()) {
    for (std::size_t i = 0; i < bounds.size(); ++i)
      refs_[i] = PrimRef{bounds[i], bounds[i].centroid(), static_cast<std::uint32_t>(i)};
    std::uint32_t threads = options.thread_count != 0
                                ? options.thread_count
                                : std::max(1u, std::thread::hardware_concurrency());
    spare_threads_.store(static_cast<int>(threads) - 1);
  }

  // Input index of the primitive in each leaf slot (valid after build).
  std::vector<std::uint32_t> primitive_order() const {
    std::vector<std::uint32_t> order(refs_.size());
    for (std::size_t i = 0; i < refs_.size(); ++i) order[i] = refs_[i].id;
    return order;
  }

  // Appends the subtree over slots [begin, end) to `out` in depth-first order; child indices are
  // relative to out[0].
  void build(std::uint32_t begin, std::uint32_t end, std::uint32_t depth,
             std::vector<gpu::BvhNode>& out) {
    Aabb box, centroid_box;
    for (std::uint32_t i = begin; i < end; ++i) {
      box.grow(refs_[i].box);
      centroid_box.grow(refs_[i].centroid);
    }
    const auto node_index = static_cast<std::uint32_t>(out.size());
    out.push_back(make_node(box, begin, end - begin));
    const std::uint32_t count = end - begin;
    if (count == 1) return;

    std::uint32_t mid = begin;
    if (depth < kMedianSplitDepth) {
      Split split = find_sah_split(begin, end, centroid_box);
      const float leaf_cost = kIntersectionCost * static_cast<float>(count);
      if (count <= options_.max_leaf_size && (split.axis < 0 || leaf_cost <= split.cost)) return;
      if (split.axis >= 0) {
        mid = partition_by_bin(begin, end, split, centroid_box);
      }
    } else if (count <= options_.max_leaf_size) {
      return;
    }
    if (mid == begin) mid = median_split(begin, end, centroid_box);

    std::vector<gpu::BvhNode> left_nodes;
    std::vector<gpu::BvhNode> right_nodes;
    if (count >= options_.parallel_threshold && acquire_thread()) {
      auto left = std::async(std::launch::async, [&] {
        build(begin, mid, depth + 1, left_nodes);
        release_thread();
      });
      build(mid, end, depth + 1, right_nodes);
      left.get();
      append_subtree(out, left_nodes);
      out[node_index].bounds_min.w = glm::uintBitsToFloat(static_cast<std::uint32_t>(out.size()));
      append_subtree(out, right_nodes);
    } else {
      build(begin, mid, depth + 1, out);
      out[node_index].bounds_min.w = glm::uintBitsToFloat(static_cast<std::uint32_t>(out.size()));
      build(mid, end, depth + 1, out);
    }
    out[node_index].bounds_max.w = glm::uintBitsToFloat(0u);  // interior
  }

 private:
  // Appends a subtree built into its own array, shifting its child indices.
  static void append_subtree(std::vector<gpu::BvhNode>& out,
                             const std::vector<gpu::BvhNode>& subtree) {
    const auto base = static_cast<std::uint32_t>(out.size());
    for (gpu::BvhNode node : subtree) {
      if (!gpu::bvh_node_is_leaf(node))
        node.bounds_min.w = glm::uintBitsToFloat(gpu::bvh_node_index(node) + base);
      out.push_back(node);
    }
  }

  // Maps a centroid to its bin along each axis of a node's centroid box (the same arithmetic for
  // binning and partitioning, so both agree on every primitive).
  struct BinMapping {
    glm::vec3 origin;
    glm::vec3 scale;  // bins per unit length; 0 on an axis where all centroids coincide
    std::uint32_t bins;
    std::uint32_t last_bin;
    std::uint32_t bin(const glm::vec3& centroid, int axis) const {
      const float f = (centroid[axis] - origin[axis]) * scale[axis];
      return std::min(static_cast<std::uint32_t>(std::max(f, 0.0f)), last_bin);
    }
  };

  // Small nodes use fewer bins (at least 4): the per-node cost of many empty bins dominates the
  // build near the leaves, and there are few distinct planes to choose from anyway.
  BinMapping bin_mapping(const Aabb& centroid_box, std::uint32_t count) const {
    BinMapping m;
    m.origin = centroid_box.min;
    m.bins = std::min(options_.bin_count, std::max(4u, count));
    const glm::vec3 extent = centroid_box.extent();
    for (int axis = 0; axis < 3; ++axis)
      m.scale[axis] = extent[axis] > 0.0f ? static_cast<float>(m.bins) / extent[axis] : 0.0f;
    m.last_bin = m.bins - 1;
    return m;
  }

  Split find_sah_split(std::uint32_t begin, std::uint32_t end, const Aabb& centroid_box) const {
    const BinMapping mapping = bin_mapping(centroid_box, end - begin);
    const std::uint32_t bins = mapping.bins;
    std::array<std::array<Aabb, kMaxBins>, 3> bin_box{};
    std::array<std::array<std::uint32_t, kMaxBins>, 3> bin_count{};
    for (std::uint32_t i = begin; i < end; ++i) {
      const PrimRef& ref = refs_[i];
      for (int axis = 0; axis < 3; ++axis) {
        const std::uint32_t b = mapping.bin(ref.centroid, axis);
        bin_box[axis][b].grow(ref.box);
        ++bin_count[axis][b];
      }
    }
    Split best;
    Aabb node_box;
    for (int axis = 0; axis < 3; ++axis) {
      if (mapping.scale[axis] == 0.0f) continue;
      // Sweep from the right: SAH term of everything in bins [b, bins).
      std::array<float, kMaxBins> right_cost{};
      Aabb right;
      std::uint32_t right_count = 0;
      for (std::uint32_t b = bins - 1; b > 0; --b) {
        right.grow(bin_box[axis][b]);
        right_count += bin_count[axis][b];
        right_cost[b] = right.area() * static_cast<float>(right_count);
      }
      right.grow(bin_box[axis][0]);
      node_box = right;
      Aabb left;
      std::uint32_t left_count = 0;
      const std::uint32_t total = end - begin;
      for (std::uint32_t b = 1; b < bins; ++b) {
        left.grow(bin_box[axis][b - 1]);
        left_count += bin_count[axis][b - 1];
        if (left_count == 0 || left_count == total) continue;
        const float cost = left.area() * static_cast<float>(left_count) + right_cost[b];
        if (cost < best.cost) best = Split{axis, b, cost};
      }
    }
    if (best.axis >= 0) {
      const float area = node_box.area();
      // A zero-area node (all primitives degenerate at one point) makes every split cost equal.
      best.cost = kTraversalCost + (area > 0.0f ? kIntersectionCost * best.cost / area : 0.0f);
    }
    return best;
  }

  std::uint32_t partition_by_bin(std::uint32_t begin, std::uint32_t end, const Split& split,
                                 const Aabb& centroid_box) {
    const BinMapping mapping = bin_mapping(centroid_box, end - begin);
    auto mid = std::partition(refs_.begin() + begin, refs_.begin() + end, [&](const PrimRef& ref) {
      return mapping.bin(ref.centroid, split.axis) < split.bin;
    });
    return static_cast<std::uint32_t>(mid - refs_.begin());
  }

  // Splits the range in two halves by centroid along the widest axis (ties by primitive index so
  // the result is fully determined).
  std::uint32_t median_split(std::uint32_t begin, std::uint32_t end, const Aabb& centroid_box) {
    const glm::vec3 e = centroid_box.extent();
    const int axis = (e.x >= e.y && e.x >= e.z) ? 0 : (e.y >= e.z ? 1 : 2);
    const std::uint32_t mid = begin + (end - begin) / 2;
    std::nth_element(refs_.begin() + begin, refs_.begin() + mid, refs_.begin() + end,
                     [&](const PrimRef& a, const PrimRef& b) {
                       const float ca = a.centroid[axis];
                       const float cb = b.centroid[axis];
                       return ca < cb || (ca == cb && a.id < b.id);
                     });
    return mid;
  }

  bool acquire_thread() {
    int spare = spare_threads_.load();
    while (spare > 0) {
      if (spare_threads_.compare_exchange_weak(spare, spare - 1)) return true;
    }
    return false;
  }
  void release_thread() { spare_threads_.fetch_add(1); }

  const BvhBuildOptions& options_;
  std::vector<PrimRef> refs_;
  std::atomic<int> spare_threads_{0};
};

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

Aabb node_bounds(const gpu::BvhNode& node) {
  Aabb box;
  box.min = glm::vec3(node.bounds_min);
  box.max = glm::vec3(node.bounds_max);
  return box;
}

BvhBuildOutput build_bvh(std::span<const Aabb> primitive_bounds, const BvhBuildOptions& options) {
  if (options.max_leaf_size == 0) throw InputError("BVH build: max_leaf_size must be at least 1");
  if (options.bin_count < 2 || options.bin_count > kMaxBins)
    throw InputError(
        fmt::format("BVH build: bin_count {} is outside [2, {}]", options.bin_count, kMaxBins));
  if (primitive_bounds.size() >= std::numeric_limits<std::uint32_t>::max() / 2)
    throw InputError(fmt::format("BVH build: {} primitives is too many", primitive_bounds.size()));
  for (std::size_t i = 0; i < primitive_bounds.size(); ++i) {
    const Aabb& b = primitive_bounds[i];
    if (!finite(b.min) || !finite(b.max) || b.empty())
      throw InputError(fmt::format("BVH build: primitive {} has a non-finite or empty box", i));
  }

  BvhBuildOutput output;
  if (primitive_bounds.empty()) return output;
  Builder builder(primitive_bounds, options);
  output.nodes.reserve(2 * primitive_bounds.size());
  builder.build(0, static_cast<std::uint32_t>(primitive_bounds.size()), 0, output.nodes);
  output.nodes.shrink_to_fit();
  output.primitive_order = builder.primitive_order();
  return output;
}

void refit_bvh(std::span<gpu::BvhNode> nodes, std::span<const Aabb> leaf_slot_bounds) {
  for (std::size_t n = nodes.size(); n-- > 0;) {
    gpu::BvhNode& node = nodes[n];
    Aabb box;
    const std::uint32_t index = gpu::bvh_node_index(node);
    if (gpu::bvh_node_is_leaf(node)) {
      const std::uint32_t count = gpu::bvh_node_count(node);
      for (std::uint32_t i = 0; i < count; ++i) box.grow(leaf_slot_bounds[index + i]);
      box = padded(box);
    } else {
      box = node_bounds(nodes[n + 1]);  // children are padded already
      box.grow(node_bounds(nodes[index]));
    }
    node.bounds_min = glm::vec4(box.min, node.bounds_min.w);
    node.bounds_max = glm::vec4(box.max, node.bounds_max.w);
  }
}

}  // namespace lantern::lighting
