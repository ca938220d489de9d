// libFuzzer entry for the level_json loader target (tests/fuzz/fuzz_targets.h); built by
// scripts/fuzz.sh.
#include <cstddef>
#include <cstdint>

#include "tests/fuzz/fuzz_targets.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  lantern::fuzz::init(LANTERN_FUZZ_ASSETS);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return lantern::fuzz::level_json(data, size);
}
