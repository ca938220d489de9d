// libFuzzer entry for the vdb loader target (tests/fuzz/fuzz_targets.h); built by scripts/fuzz.sh.
#include <cstddef>
#include <cstdint>

#include "engine/core/log.h"
#include "tests/fuzz/fuzz_targets.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  lantern::log::set_level(lantern::log::Level::Error);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return lantern::fuzz::vdb(data, size);
}
