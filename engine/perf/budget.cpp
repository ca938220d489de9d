#include "engine/perf/budget.h"

#include <fmt/format.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "engine/core/error.h"

namespace lantern::perf {
namespace {

using nlohmann::json;

double positive_number(const json& j, const std::string& where, const std::string& source) {
  if (!j.is_number()) throw InputError(fmt::format("{}: {} must be a number", source, where));
  const double v = j.get<double>();
  if (!(v > 0.0) || v > 1e9) {
    throw InputError(fmt::format("{}: {} must be positive and finite, got {}", source, where, v));
  }
  return v;
}

BudgetLimits parse_limits(const json& j, const std::string& where, const std::string& source) {
  if (!j.is_object()) throw InputError(fmt::format("{}: {} must be an object", source, where));
  BudgetLimits limits;
  for (const auto& [key, value] : j.items()) {
    if (key == "frame") {
      limits.frame = positive_number(value, where + ".frame", source);
    } else if (key == "passes") {
      if (!value.is_object()) {
        throw InputError(fmt::format("{}: {}.passes must be an object", source, where));
      }
      for (const auto& [pass, limit] : value.items()) {
        limits.passes[pass] = positive_number(limit, where + ".passes." + pass, source);
      }
    } else if (key != "device") {
      throw InputError(fmt::format("{}: unknown field '{}' in {}", source, key, where));
    }
  }
  return limits;
}

std::string string_field(const json& j, const char* key, const std::string& source) {
  if (!j.is_string()) throw InputError(fmt::format("{}: '{}' must be a string", source, key));
  return j.get<std::string>();
}

double statistic_of(const Summary& s, const std::string& statistic) {
  if (statistic == "p95") return s.p95;
  if (statistic == "p99") return s.p99;
  if (statistic == "max") return s.max;
  return s.median;
}

void check_limits(const BudgetLimits& limits, const BenchMeasurement& m, const Budget& b,
                  double scale, const std::string& unit, BudgetResult& result) {
  auto check = [&](const std::string& what, const Summary& s, double limit) {
    const double measured = statistic_of(s, b.statistic) / scale;
    result.checked.push_back(fmt::format("{:<24} {} {:9.3f} {} (limit {:.3f}){}", what,
                                         b.statistic, measured, unit, limit,
                                         measured > limit ? "  OVER BUDGET" : ""));
    if (measured > limit) result.violations.push_back({what, measured, limit, unit});
  };
  if (limits.frame) check("frame", m.frame, *limits.frame);
  for (const auto& [pass, limit] : limits.passes) {
    auto it = m.passes.find(pass);
    if (it == m.passes.end()) {
      throw InputError(fmt::format("{}: budget names pass '{}', which this run does not have",
                                   b.source, pass));
    }
    check(pass, it->second, limit);
  }
}

}  // namespace

Budget parse_budget(const std::string& json_text, const std::string& source) {
  json j;
  try {
    j = json::parse(json_text);
  } catch (const json::parse_error& e) {
    throw InputError(fmt::format("{}: not valid JSON: {}", source, e.what()));
  }
  if (!j.is_object()) throw InputError(fmt::format("{}: a budget must be a JSON object", source));
  Budget b;
  b.source = source;
  for (const auto& [key, value] : j.items()) {
    if (key == "level") {
      b.level = string_field(value, "level", source);
    } else if (key == "integrator") {
      b.integrator = string_field(value, "integrator", source);
    } else if (key == "preset") {
      b.preset = string_field(value, "preset", source);
    } else if (key == "size") {
      if (!value.is_array() || value.size() != 2 || !value[0].is_number_unsigned() ||
          !value[1].is_number_unsigned()) {
        throw InputError(fmt::format("{}: 'size' must be [width, height]", source));
      }
      b.size = std::pair{value[0].get<unsigned>(), value[1].get<unsigned>()};
    } else if (key == "statistic") {
      b.statistic = string_field(value, "statistic", source);
      if (b.statistic != "median" && b.statistic != "p95" && b.statistic != "p99" &&
          b.statistic != "max") {
        throw InputError(fmt::format("{}: statistic '{}' (expected median, p95, p99 or max)",
                                     source, b.statistic));
      }
    } else if (key == "relative") {
      b.relative = parse_limits(value, "relative", source);
    } else if (key == "absolute") {
      if (!value.is_array()) throw InputError(fmt::format("{}: 'absolute' must be a list", source));
      for (std::size_t i = 0; i < value.size(); ++i) {
        const std::string where = fmt::format("absolute[{}]", i);
        if (!value[i].is_object() || !value[i].contains("device")) {
          throw InputError(fmt::format("{}: {} needs a \"device\"", source, where));
        }
        b.absolute.emplace_back(string_field(value[i]["device"], "device", source),
                                parse_limits(value[i], where, source));
      }
    } else if (key != "comment") {
      throw InputError(fmt::format("{}: unknown field '{}'", source, key));
    }
  }
  return b;
}

Budget load_budget(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(fmt::format("budget file {} cannot be read", path.string()));
  std::ostringstream text;
  text << in.rdbuf();
  return parse_budget(text.str(), path.string());
}

BudgetResult check_budget(const Budget& b, const BenchMeasurement& m) {
  auto mismatch = [&](const char* what, const std::string& budget, const std::string& run) {
    throw InputError(
        fmt::format("{}: budget is for {} {}, this run is {}", b.source, what, budget, run));
  };
  if (b.level && *b.level != m.level) mismatch("level", *b.level, m.level);
  if (b.integrator && *b.integrator != m.integrator) {
    mismatch("integrator", *b.integrator, m.integrator);
  }
  if (b.preset && *b.preset != m.preset) mismatch("preset", *b.preset, m.preset);
  if (b.size && *b.size != m.size) {
    mismatch("size", fmt::format("{}x{}", b.size->first, b.size->second),
             fmt::format("{}x{}", m.size.first, m.size.second));
  }
  BudgetResult result;
  bool any = false;
  if (b.relative) {
    if (!(m.calibration_ms > 0.0)) {
      throw InputError(fmt::format("{}: relative limits need a calibration time", b.source));
    }
    check_limits(*b.relative, m, b, m.calibration_ms, "x calibration", result);
    any = true;
  }
  for (const auto& [device, limits] : b.absolute) {
    if (m.device.find(device) == std::string::npos) continue;
    check_limits(limits, m, b, 1.0, "ms", result);
    any = true;
  }
  if (!any) {
    throw InputError(fmt::format(
        "{}: no limit applies (no \"relative\" limits and no \"absolute\" entry for device '{}')",
        b.source, m.device));
  }
  return result;
}

}  // namespace lantern::perf
