#include "engine/core/log.h"

#include <atomic>
#include <cstdio>
#include <mutex>

namespace lantern::log {
namespace {
std::atomic<Level> g_level{Level::Info};
std::mutex g_mutex;
constexpr const char* kPrefix[] = {"debug: ", "", "warning: ", "error: "};
}  // namespace

void set_level(Level l) { g_level.store(l, std::memory_order_relaxed); }
Level level() { return g_level.load(std::memory_order_relaxed); }

void write(Level l, std::string_view message) {
  std::lock_guard lock(g_mutex);
  std::fprintf(stderr, "%s%.*s\n", kPrefix[static_cast<int>(l)], static_cast<int>(message.size()),
               message.data());
}

}  // namespace lantern::log
