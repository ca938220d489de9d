// Strict typed JSON object reading with JSON-pointer error places; JSON parse with line:column.
#include "engine/level/json_object.h"

#include <fmt/format.h>

#include <cmath>

#include "engine/core/error.h"

namespace lantern {
namespace {

const char* type_name(const nlohmann::json& v) {
  return v.type_name();
}

float finite_number(const nlohmann::json& v, const std::string& where,
                    const std::filesystem::path& file) {
  if (!v.is_number())
    throw InputError(
        fmt::format("{}: {}: expected a number, got {}", file.string(), where, type_name(v)));
  const double d = v.get<double>();
  if (!std::isfinite(d) || std::abs(d) > 3.0e38)
    throw InputError(fmt::format("{}: {}: number {} is not finite", file.string(), where, d));
  return static_cast<float>(d);
}

template <int N>
glm::vec<N, float> vector(const nlohmann::json& v, const std::string& where,
                          const std::filesystem::path& file) {
  if (!v.is_array() || v.size() != N)
    throw InputError(
        fmt::format("{}: {}: expected an array of {} numbers, got {}", file.string(), where, N,
                    v.is_array() ? fmt::format("{} values", v.size()) : std::string(type_name(v))));
  glm::vec<N, float> out;
  for (int i = 0; i < N; ++i) out[i] = finite_number(v[i], fmt::format("{}/{}", where, i), file);
  return out;
}

}  // namespace

std::string pointer_token(std::string_view key) {
  std::string out;
  for (char c : key) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return out;
}

JsonObject::JsonObject(const nlohmann::json& value, std::string pointer,
                       const std::filesystem::path& file)
    : value_(value), pointer_(std::move(pointer)), file_(file) {
  if (!value_.is_object())
    throw InputError(fmt::format("{}: {}: expected an object, got {}", file_.string(),
                                 pointer_.empty() ? "/" : pointer_, type_name(value_)));
}

std::string JsonObject::pointer(std::string_view key) const {
  return pointer_ + "/" + pointer_token(key);
}

bool JsonObject::has(std::string_view key) const {
  return value_.contains(key);
}

std::vector<std::string> JsonObject::keys() const {
  std::vector<std::string> out;
  for (auto it = value_.begin(); it != value_.end(); ++it) out.push_back(it.key());
  return out;
}

const nlohmann::json& JsonObject::raw(std::string_view key) {
  auto it = value_.find(key);
  if (it == value_.end()) fail(key, "is required");
  read_.emplace(key);
  return *it;
}

void JsonObject::fail(std::string_view key, std::string_view message) const {
  throw InputError(fmt::format("{}: {}: {}", file_.string(), pointer(key), message));
}

void JsonObject::fail(std::string_view message) const {
  throw InputError(
      fmt::format("{}: {}: {}", file_.string(), pointer_.empty() ? "/" : pointer_, message));
}

JsonObject JsonObject::object(std::string_view key) {
  return JsonObject(raw(key), pointer(key), file_);
}

float JsonObject::number(std::string_view key) {
  return finite_number(raw(key), pointer(key), file_);
}

float JsonObject::number(std::string_view key, float fallback) {
  return has(key) ? number(key) : fallback;
}

std::int64_t JsonObject::integer(std::string_view key, std::int64_t fallback, std::int64_t lo,
                                 std::int64_t hi) {
  if (!has(key)) return fallback;
  const nlohmann::json& v = raw(key);
  if (v.is_number_float() && std::isfinite(v.get<double>()) &&
      v.get<double>() == std::floor(v.get<double>()) && std::abs(v.get<double>()) < 9.0e18) {
    // Accept 1e6-style integers written as floats.
  } else if (!v.is_number_integer()) {
    fail(key, fmt::format("expected an integer, got {}", v.dump()));
  }
  const double d = v.get<double>();
  if (d < static_cast<double>(lo) || d > static_cast<double>(hi))
    fail(key, fmt::format("{} is out of range [{}, {}]", v.dump(), lo, hi));
  return v.is_number_float() ? static_cast<std::int64_t>(d) : v.get<std::int64_t>();
}

std::string JsonObject::string(std::string_view key) {
  const nlohmann::json& v = raw(key);
  if (!v.is_string()) fail(key, fmt::format("expected a string, got {}", type_name(v)));
  return v.get<std::string>();
}

std::string JsonObject::string(std::string_view key, std::string fallback) {
  return has(key) ? string(key) : fallback;
}

bool JsonObject::boolean(std::string_view key, bool fallback) {
  if (!has(key)) return fallback;
  const nlohmann::json& v = raw(key);
  if (!v.is_boolean()) fail(key, fmt::format("expected true or false, got {}", type_name(v)));
  return v.get<bool>();
}

glm::vec2 JsonObject::vec2(std::string_view key, glm::vec2 fallback) {
  return has(key) ? vector<2>(raw(key), pointer(key), file_) : fallback;
}
glm::vec3 JsonObject::vec3(std::string_view key) {
  return vector<3>(raw(key), pointer(key), file_);
}
glm::vec3 JsonObject::vec3(std::string_view key, glm::vec3 fallback) {
  return has(key) ? vec3(key) : fallback;
}
glm::vec4 JsonObject::vec4(std::string_view key, glm::vec4 fallback) {
  return has(key) ? vector<4>(raw(key), pointer(key), file_) : fallback;
}

glm::quat JsonObject::quat(std::string_view key, glm::quat fallback) {
  if (!has(key)) return fallback;
  const glm::vec4 v = vector<4>(raw(key), pointer(key), file_);
  if (glm::length(v) < 1e-6f) fail(key, "quaternion has zero length");
  const glm::vec4 n = glm::normalize(v);
  return glm::quat(n.w, n.x, n.y, n.z);
}

void JsonObject::finish() const {
  for (auto it = value_.begin(); it != value_.end(); ++it) {
    if (read_.count(it.key())) continue;
    std::string known;
    for (const auto& k : read_) known += (known.empty() ? "" : ", ") + k;
    fail(it.key(), fmt::format("unknown key '{}'{}", it.key(),
                               known.empty() ? "" : " (this object used: " + known + ")"));
  }
}

const nlohmann::json& expect_array(const nlohmann::json& value, const std::string& pointer,
                                   const std::filesystem::path& file) {
  if (!value.is_array())
    throw InputError(
        fmt::format("{}: {}: expected an array, got {}", file.string(), pointer, type_name(value)));
  return value;
}

namespace {

// 1-based line and column of byte `offset` in `text`.
std::pair<std::size_t, std::size_t> line_column(const std::string& text, std::size_t offset) {
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i < std::min(offset, text.size()); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

// nlohmann's message without its "[json.exception.x.NNN] " prefix.
std::string plain_message(const nlohmann::json::exception& e) {
  std::string what = e.what();
  if (auto bracket = what.find("] "); bracket != std::string::npos) what = what.substr(bracket + 2);
  return what;
}

}  // namespace

nlohmann::json parse_json_text(const std::string& text, const std::filesystem::path& file) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte is 1-based: the position of the offending character.
    const auto [line, column] = line_column(text, e.byte > 0 ? e.byte - 1 : 0);
    std::string what = plain_message(e);
    // Drop the "parse error at line 1, column 2: " part: the place is given as file:line:column.
    if (auto colon = what.find(": "); colon != std::string::npos) what = what.substr(colon + 2);
    throw InputError(
        fmt::format("{}:{}:{}: malformed JSON: {}", file.string(), line, column, what));
  } catch (const nlohmann::json::exception& e) {
    // E.g. "number overflow parsing '1e999'" (a number that is Inf as a double): locate the token.
    const std::string what = plain_message(e);
    std::size_t offset = std::string::npos;
    if (auto open = what.find('\''), close = what.rfind('\'');
        open != std::string::npos && close > open)
      offset = text.find(what.substr(open + 1, close - open - 1));
    if (offset == std::string::npos)
      throw InputError(fmt::format("{}: malformed JSON: {}", file.string(), what));
    const auto [line, column] = line_column(text, offset);
    throw InputError(
        fmt::format("{}:{}:{}: malformed JSON: {}", file.string(), line, column, what));
  }
}

}  // namespace lantern
