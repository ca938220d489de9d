// Generational handles: a 32-bit value packing a slot index and a generation counter, so a handle
// to a freed slot is told apart from a handle to the slot's next occupant. Used by the ECS for
// entities; usable for any pool of slots (`Handle<struct MyTag>`).
#pragma once

#include <cstdint>
#include <functional>

namespace lantern {

template <class Tag>
class Handle {
 public:
  static constexpr int kIndexBits = 22;  // 4M live slots
  static constexpr int kGenerationBits = 32 - kIndexBits;
  static constexpr std::uint32_t kIndexMask = (1u << kIndexBits) - 1u;
  // The all-ones index is never allocated: it marks the null handle.
  static constexpr std::uint32_t kMaxIndex = kIndexMask - 1u;
  // A slot whose generation reaches this value is retired instead of wrapping to 0, so an old
  // handle can never compare equal to a new one. Bound: 2^32 creations per pool in the worst
  // case (every slot retired): ~20 hours of 60k creations per second.
  static constexpr std::uint32_t kMaxGeneration = (1u << kGenerationBits) - 1u;

  constexpr Handle() = default;
  constexpr Handle(std::uint32_t index, std::uint32_t generation)
      : bits_((generation << kIndexBits) | (index & kIndexMask)) {}

  static constexpr Handle null() { return Handle{}; }
  static constexpr Handle from_bits(std::uint32_t bits) {
    Handle h;
    h.bits_ = bits;
    return h;
  }

  constexpr std::uint32_t index() const { return bits_ & kIndexMask; }
  constexpr std::uint32_t generation() const { return bits_ >> kIndexBits; }
  constexpr std::uint32_t bits() const { return bits_; }
  constexpr bool is_null() const { return index() == kIndexMask; }
  explicit constexpr operator bool() const { return !is_null(); }

  friend constexpr bool operator==(Handle a, Handle b) { return a.bits_ == b.bits_; }
  friend constexpr auto operator<=>(Handle a, Handle b) { return a.bits_ <=> b.bits_; }

 private:
  std::uint32_t bits_ = 0xFFFFFFFFu;
};

}  // namespace lantern

template <class Tag>
struct std::hash<lantern::Handle<Tag>> {
  std::size_t operator()(lantern::Handle<Tag> h) const noexcept {
    return std::hash<std::uint32_t>{}(h.bits());
  }
};
