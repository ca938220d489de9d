// Chrome trace event JSON (chrome://tracing, https://ui.perfetto.dev): complete events ("ph": "X")
// on named tracks, written by `lantern bench --trace FILE` with the CPU systems and GPU passes of
// every frame. Times are microseconds from the start of the run.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace lantern::perf {

class ChromeTrace {
 public:
  // A track is a row in the viewer ("CPU systems", "GPU passes"); returns its id.
  int track(const std::string& name);
  void event(int track, const std::string& name, double start_us, double duration_us,
             const std::string& category = "frame");
  std::size_t size() const { return events_.size(); }
  // Writes atomically (temp file + rename); RuntimeError when the file cannot be written.
  void write(const std::filesystem::path& path) const;
  std::string json() const;

 private:
  struct Event {
    int track;
    std::string name;
    std::string category;
    double start_us;
    double duration_us;
  };
  std::vector<std::string> tracks_;
  std::vector<Event> events_;
};

}  // namespace lantern::perf
