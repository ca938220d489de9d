// libFuzzer entry for the image decoding target (tests/fuzz/fuzz_targets.h); built by
// scripts/fuzz.sh.
#include <cstddef>
#include <cstdint>

#include "tests/fuzz/fuzz_targets.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  lantern::fuzz::init(LANTERN_FUZZ_ASSETS);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return lantern::fuzz::image(data, size);
}
