// Errors that reach the user. InputError: the user's input is wrong (bad flag, file, level data)
// and the `lantern` command exits 2. RuntimeError: a run failed (device lost, I/O error), exit 1.
// Always-on checks for bad input use these; internal invariants use LANTERN_ASSERT (debug only).
#pragma once

#include <cassert>
#include <stdexcept>
#include <string>

namespace lantern {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class RuntimeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace lantern

// Internal invariant: checked in debug builds only.
#define LANTERN_ASSERT(cond) assert(cond)
