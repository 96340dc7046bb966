#pragma once
// Looking up the named figures (error norms, diagnostics) a reference writes (stagger/output.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

#include "stagger/output.hpp"

namespace stagger::testing {

/// The value named `name`; a test failure and NaN if there is none.
inline double value_of(const NamedValues& values, const std::string& name) {
  for (const auto& [key, value] : values)
    if (key == name) return value;
  ADD_FAILURE() << "no value named " << name;
  return NAN;
}

inline std::map<std::string, double> as_map(const NamedValues& values) {
  return {values.begin(), values.end()};
}

}  // namespace stagger::testing
