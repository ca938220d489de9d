// SPIR-V struct-layout reader for the layout test (see spirv_layout.h).
#include "spirv_layout.h"

#include <spirv/unified1/spirv.h>

#include <fstream>
#include <stdexcept>
#include <unordered_map>

namespace lantern::test {
namespace {

// A literal string starting at words[first], nul-terminated, packed little-endian 4 per word.
std::string literal_string(const std::vector<std::uint32_t>& words, std::size_t first,
                           std::size_t end) {
  std::string s;
  for (std::size_t i = first; i < end; ++i) {
    for (int byte = 0; byte < 4; ++byte) {
      char c = static_cast<char>((words[i] >> (8 * byte)) & 0xffu);
      if (c == '\0') return s;
      s.push_back(c);
    }
  }
  return s;
}

struct StructId {
  std::vector<std::uint32_t> member_types;
  std::vector<std::string> member_names;
  std::vector<std::int64_t> member_offsets;
};

bool has_offsets(const SpirvStruct& s) {
  for (std::int64_t offset : s.member_offsets)
    if (offset >= 0) return true;
  return false;
}

}  // namespace

SpirvStructs parse_spirv_structs(const std::vector<std::uint32_t>& words) {
  if (words.size() < 5 || words[0] != SpvMagicNumber) {
    throw std::runtime_error("not a SPIR-V module (bad magic number or too short)");
  }
  std::unordered_map<std::uint32_t, std::string> names;
  std::unordered_map<std::uint32_t, StructId> structs;
  std::unordered_map<std::uint32_t, std::int64_t> array_strides;   // array type id -> stride
  std::unordered_map<std::uint32_t, std::uint32_t> array_element;  // array type id -> element
  std::unordered_map<std::uint32_t, std::map<std::uint32_t, std::string>> member_names;
  std::unordered_map<std::uint32_t, std::map<std::uint32_t, std::int64_t>> member_offsets;

  for (std::size_t at = 5; at < words.size();) {
    std::uint32_t count = words[at] >> 16;
    std::uint32_t opcode = words[at] & 0xffffu;
    if (count == 0 || at + count > words.size()) {
      throw std::runtime_error("truncated SPIR-V instruction at word " + std::to_string(at));
    }
    const std::size_t end = at + count;
    switch (opcode) {
      case SpvOpName:
        names[words[at + 1]] = literal_string(words, at + 2, end);
        break;
      case SpvOpMemberName:
        member_names[words[at + 1]][words[at + 2]] = literal_string(words, at + 3, end);
        break;
      case SpvOpMemberDecorate:
        if (count >= 5 && words[at + 3] == SpvDecorationOffset) {
          member_offsets[words[at + 1]][words[at + 2]] = words[at + 4];
        }
        break;
      case SpvOpDecorate:
        if (count >= 4 && words[at + 2] == SpvDecorationArrayStride) {
          array_strides[words[at + 1]] = words[at + 3];
        }
        break;
      case SpvOpTypeStruct:
        structs[words[at + 1]].member_types.assign(words.begin() + static_cast<long>(at + 2),
                                                   words.begin() + static_cast<long>(end));
        break;
      case SpvOpTypeArray:
      case SpvOpTypeRuntimeArray:
        array_element[words[at + 1]] = words[at + 2];
        break;
      default:
        break;
    }
    at = end;
  }

  SpirvStructs result;
  for (auto& [id, s] : structs) {
    auto name = names.find(id);
    if (name == names.end() || name->second.empty()) continue;
    SpirvStruct out;
    out.name = name->second;
    std::size_t n = s.member_types.size();
    out.member_names.assign(n, "");
    out.member_offsets.assign(n, -1);
    for (auto& [index, member] : member_names[id])
      if (index < n) out.member_names[index] = member;
    for (auto& [index, offset] : member_offsets[id])
      if (index < n) out.member_offsets[index] = offset;
    for (auto& [array, element] : array_element)
      if (element == id && array_strides.count(array)) out.array_stride = array_strides[array];
    // Prefer the decorated copy when glslang emitted the same name for several struct ids.
    bool decorated = !member_offsets[id].empty();
    auto existing = result.find(out.name);
    if (existing == result.end() || (decorated && !has_offsets(existing->second))) {
      result[out.name] = out;
    }
  }
  return result;
}

std::vector<std::uint32_t> read_spirv_file(const std::string& path) {
  std::ifstream file(path, std::ios::binary | std::ios::ate);
  if (!file) throw std::runtime_error("cannot open SPIR-V file " + path);
  std::streamsize bytes = file.tellg();
  if (bytes <= 0 || bytes % 4 != 0) {
    throw std::runtime_error("SPIR-V file " + path + " has " + std::to_string(bytes) +
                             " bytes (want a positive multiple of 4)");
  }
  std::vector<std::uint32_t> words(static_cast<std::size_t>(bytes) / 4);
  file.seekg(0);
  file.read(reinterpret_cast<char*>(words.data()), bytes);
  return words;
}

}  // namespace lantern::test
