// libFuzzer entry for the vdb loader target (tests/fuzz/fuzz_targets.h); built by scripts/fuzz.sh.
//
// OpenVDB 10 allocates whatever length a file states for a metadata string before it reads it.
// On a real machine an impossible length ends in std::bad_alloc (or a short read), which the
// reader turns into one InputError; under libFuzzer such a malloc is reported as an
// out-of-memory crash instead (ASan's operator new does not throw). This harness therefore
// replaces the global (non-aligned) operator new with one that throws std::bad_alloc above
// 512 MiB, as an allocator on a small machine would, so the fuzzer checks the reader's handling
// of it and goes on. The cap is above every allocation a grid within the reader's own limits
// needs (2^25 voxels: 128 MiB staged, ~182 MiB of 9^3 bricks, a vector's doubling included), so
// a file the engine would load never trips it, and below libFuzzer's 1 GiB malloc limit. Only
// here: the replay test and the engine use the normal allocator (this binary gives up ASan's
// new/delete mismatch reports for it).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>

#include "engine/core/log.h"
#include "tests/fuzz/fuzz_targets.h"

namespace {
constexpr std::size_t kLargestAllocation = std::size_t{512} << 20;

void* allocate(std::size_t size) {
  if (size > kLargestAllocation) throw std::bad_alloc();
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
}  // namespace

void* operator new(std::size_t size) { return allocate(size); }
void* operator new[](std::size_t size) { return allocate(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  return size > kLargestAllocation ? nullptr : std::malloc(size == 0 ? 1 : size);
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  return size > kLargestAllocation ? nullptr : std::malloc(size == 0 ? 1 : size);
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  lantern::log::set_level(lantern::log::Level::Error);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return lantern::fuzz::vdb(data, size);
}
