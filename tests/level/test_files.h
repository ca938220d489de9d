// Helpers for level tests: the test data directory, scratch files, and minimal glTF documents
// built in memory (one triangle list, base64 buffer) so bad-input variants need no committed files.
#pragma once

#include <filesystem>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace lantern::test {

std::filesystem::path data_dir();
// A fresh file path under a per-process scratch directory.
std::filesystem::path scratch(const std::string& name);
void write_text(const std::filesystem::path& path, const std::string& text);

// The binary buffer triangle_gltf embeds: positions (float3) then indices (u32).
std::vector<unsigned char> triangle_buffer(const std::vector<glm::vec3>& positions,
                                           const std::vector<std::uint32_t>& indices);
// Writes a .glb: `document` (whose buffer 0 has no uri) as the JSON chunk and `bin` as the BIN
// chunk.
void write_glb(const std::filesystem::path& path, const nlohmann::json& document,
               const std::vector<unsigned char>& bin);

// A glTF document with one mesh (POSITION + u32 indices), one node and one material.
nlohmann::json triangle_gltf(const std::vector<glm::vec3>& positions,
                             const std::vector<std::uint32_t>& indices);

// Runs `f` and returns the InputError message, or fails the test if none was thrown.
template <class F>
std::string input_error_of(F&& f);

}  // namespace lantern::test

#include <gtest/gtest.h>

#include "engine/core/error.h"

template <class F>
std::string lantern::test::input_error_of(F&& f) {
  try {
    f();
  } catch (const lantern::InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected InputError, got another exception: " << e.what();
    return {};
  }
  ADD_FAILURE() << "expected InputError, nothing was thrown";
  return {};
}
