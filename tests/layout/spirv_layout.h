// Test-only reader of struct layouts in a SPIR-V module: for each named struct, its member names,
// Offset decorations and the ArrayStride of arrays of it. Just enough for the layout test.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace lantern::test {

struct SpirvStruct {
  std::string name;
  std::vector<std::string> member_names;     // by member index ("" when unnamed)
  std::vector<std::int64_t> member_offsets;  // by member index (-1 when undecorated)
  std::int64_t array_stride = -1;            // stride of an array of this struct (-1: none)
};

// Structs by OpName. A name used by several struct ids keeps the one with Offset decorations.
using SpirvStructs = std::map<std::string, SpirvStruct>;

// Parses SPIR-V words; throws std::runtime_error on a malformed module.
SpirvStructs parse_spirv_structs(const std::vector<std::uint32_t>& words);

// Reads a .spv file as words; throws std::runtime_error naming the path on failure.
std::vector<std::uint32_t> read_spirv_file(const std::string& path);

}  // namespace lantern::test
