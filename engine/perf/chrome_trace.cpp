#include "engine/perf/chrome_trace.h"

#include <fmt/format.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "engine/core/error.h"

namespace lantern::perf {

int ChromeTrace::track(const std::string& name) {
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    if (tracks_[i] == name) return static_cast<int>(i);
  }
  tracks_.push_back(name);
  return static_cast<int>(tracks_.size() - 1);
}

void ChromeTrace::event(int track, const std::string& name, double start_us, double duration_us,
                        const std::string& category) {
  events_.push_back({track, name, category, start_us, duration_us});
}

std::string ChromeTrace::json() const {
  nlohmann::json events = nlohmann::json::array();
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    events.push_back({{"name", "thread_name"},
                      {"ph", "M"},
                      {"pid", 1},
                      {"tid", i},
                      {"args", {{"name", tracks_[i]}}}});
  }
  for (const Event& e : events_) {
    events.push_back({{"name", e.name},
                      {"cat", e.category},
                      {"ph", "X"},
                      {"pid", 1},
                      {"tid", e.track},
                      {"ts", e.start_us},
                      {"dur", e.duration_us}});
  }
  return nlohmann::json{{"traceEvents", events}, {"displayTimeUnit", "ms"}}.dump(1);
}

void ChromeTrace::write(const std::filesystem::path& path) const {
  const std::filesystem::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    if (!out) throw RuntimeError(fmt::format("cannot write trace {}", path.string()));
    out << json();
    if (!out.flush()) throw RuntimeError(fmt::format("cannot write trace {}", path.string()));
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp);
    throw RuntimeError(fmt::format("cannot write trace {}: {}", path.string(), ec.message()));
  }
}

}  // namespace lantern::perf
