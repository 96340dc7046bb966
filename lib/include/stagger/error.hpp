#pragma once
/// @file error.hpp
/// The one exception type of the library. Every message names what is wrong and where
/// (file:line of the input, zone or point id, cycle and time) and, where possible, what to do.
#include <stdexcept>
#include <string>

namespace stagger {

/// Thrown by every library call that rejects user data or cannot continue a run.
class Error : public std::runtime_error {
 public:
  /// `message`: one line naming what is wrong, where, and what to do.
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace stagger
