#pragma once
// The one error type for bad outside input (files, user parameters).
#include <stdexcept>
#include <string>

namespace mostyle {

// A full sentence that says where, e.g. "walk.bvh:42: expected CHANNELS, found '{'".
// Thrown by the engine, caught at the edges (CLI, worker, UI) and shown as it is.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace mostyle
