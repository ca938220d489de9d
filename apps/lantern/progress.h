// Progress of a long command (capture, trade): a redrawn bar on a terminal, plain lines
// otherwise (logs, CI), nothing with --quiet.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

namespace lantern::app {

class Progress {
 public:
  Progress(std::string label, std::uint64_t total, bool quiet);
  ~Progress();
  // Marks `done` of `total` finished, with a short note (e.g. "frame 12: 31.2 ms").
  void update(std::uint64_t done, const std::string& note = "");
  void finish();

 private:
  std::string label_;
  std::uint64_t total_;
  bool quiet_;
  bool terminal_;
  bool finished_ = false;
  std::uint64_t last_line_ = 0;  // plain mode: the last step printed
  std::chrono::steady_clock::time_point start_;
};

}  // namespace lantern::app
