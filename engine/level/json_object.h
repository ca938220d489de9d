// Strict, typed reading of one JSON object from a level file. Every error names the file and the
// JSON pointer of the value; keys nobody read are reported as unknown by finish().
#pragma once

#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace lantern {

class JsonObject {
 public:
  // Throws InputError unless `value` is an object.
  JsonObject(const nlohmann::json& value, std::string pointer, const std::filesystem::path& file);

  bool has(std::string_view key) const;
  std::vector<std::string> keys() const;            // sorted (nlohmann keeps object keys sorted)
  const nlohmann::json& raw(std::string_view key);  // marks the key read; throws if missing
  std::string pointer() const { return pointer_; }
  std::string pointer(std::string_view key) const;
  const std::filesystem::path& file() const { return file_; }

  JsonObject object(std::string_view key);
  float number(std::string_view key);
  float number(std::string_view key, float fallback);
  // An integer in [lo, hi]; the bound is part of the message when exceeded.
  std::int64_t integer(std::string_view key, std::int64_t fallback, std::int64_t lo,
                       std::int64_t hi);
  std::string string(std::string_view key);
  std::string string(std::string_view key, std::string fallback);
  bool boolean(std::string_view key, bool fallback);
  glm::vec2 vec2(std::string_view key, glm::vec2 fallback);
  glm::vec3 vec3(std::string_view key);
  glm::vec3 vec3(std::string_view key, glm::vec3 fallback);
  glm::vec4 vec4(std::string_view key, glm::vec4 fallback);
  // [x, y, z, w] unit quaternion (normalised; zero length is an error).
  glm::quat quat(std::string_view key, glm::quat fallback);

  // Reports the first key that was never read as unknown, listing the accepted ones.
  void finish() const;
  [[noreturn]] void fail(std::string_view key, std::string_view message) const;
  [[noreturn]] void fail(std::string_view message) const;

 private:
  const nlohmann::json& value_;
  std::string pointer_;
  const std::filesystem::path& file_;
  std::set<std::string, std::less<>> read_;
};

// A value at `pointer` that must be an array; throws otherwise.
const nlohmann::json& expect_array(const nlohmann::json& value, const std::string& pointer,
                                   const std::filesystem::path& file);

// Escapes a key for a JSON pointer (RFC 6901).
std::string pointer_token(std::string_view key);

// Parses `text` read from `file`; a syntax error names the file and line:column.
nlohmann::json parse_json_text(const std::string& text, const std::filesystem::path& file);

}  // namespace lantern
