#include "lighting/lights/alias_table.h"

#include <fmt/format.h>

#include <cmath>

#include "engine/core/error.h"

namespace lantern::lighting {

AliasTable::AliasTable(std::span<const float> weights) {
  const std::size_t n = weights.size();
  if (n == 0) throw InputError("alias table: no weights");
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(weights[i]) || weights[i] < 0.0f)
      throw InputError(fmt::format("alias table: weight {} is {} (must be finite and >= 0)", i,
                                   weights[i]));
    total_ += weights[i];
  }
  if (!(total_ > 0.0)) throw InputError("alias table: all weights are zero");

  // Vose: scale weights so the mean is 1, then pair each under-full slot with an over-full one.
  entries_.resize(n);
  std::vector<double> scaled(n);
  std::vector<std::uint32_t> small, large;
  small.reserve(n);
  large.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    scaled[i] = weights[i] * static_cast<double>(n) / total_;
    entries_[i].pdf = static_cast<float>(weights[i] / total_);
    (scaled[i] < 1.0 ? small : large).push_back(static_cast<std::uint32_t>(i));
  }
  while (!small.empty() && !large.empty()) {
    const std::uint32_t s = small.back();
    small.pop_back();
    const std::uint32_t l = large.back();
    entries_[s].threshold = static_cast<float>(scaled[s]);
    entries_[s].alias = l;
    scaled[l] = (scaled[l] + scaled[s]) - 1.0;
    if (scaled[l] < 1.0) {
      large.pop_back();
      small.push_back(l);
    }
  }
  // Whatever remains is full up to rounding: it keeps its own index.
  for (std::uint32_t i : large) entries_[i] = {1.0f, i, entries_[i].pdf, 0u};
  for (std::uint32_t i : small) entries_[i] = {1.0f, i, entries_[i].pdf, 0u};
}

std::uint32_t AliasTable::sample(float u0, float u1) const {
  const auto count = static_cast<std::uint32_t>(entries_.size());
  const std::uint32_t slot = gpu::alias_slot(count, u0);
  return gpu::alias_select(u1, entries_[slot], slot);
}

}  // namespace lantern::lighting
