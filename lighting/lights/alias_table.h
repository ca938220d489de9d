// Builds a Walker/Vose alias table over non-negative weights (e.g. light power) so that an index
// is drawn in O(1) with probability weight/total. The entry layout is shaders/shared/alias_table.h.
#pragma once

#include <span>
#include <vector>

#include "shared/alias_table.h"

namespace lantern::lighting {

class AliasTable {
 public:
  AliasTable() = default;
  // Weights must be finite and >= 0 with a positive sum; throws lantern::InputError otherwise.
  explicit AliasTable(std::span<const float> weights);

  const std::vector<gpu::AliasEntry>& entries() const { return entries_; }
  std::size_t size() const { return entries_.size(); }
  double total_weight() const { return total_; }
  // Probability of drawing index i (weight_i / total).
  float pdf(std::size_t i) const { return entries_[i].pdf; }
  // Draws an index from two uniform numbers in [0,1).
  std::uint32_t sample(float u0, float u1) const;

 private:
  std::vector<gpu::AliasEntry> entries_;
  double total_ = 0.0;
};

}  // namespace lantern::lighting
