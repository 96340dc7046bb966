#pragma once
/// @file number_text.hpp
/// A double as text that reads back exactly, for messages and for .geo parameters.
#include <sstream>
#include <string>

namespace stagger::meshgen {

/// `value` with 17 significant digits (the default stream format otherwise).
inline std::string number_text(double value) {
  std::ostringstream s;
  s.precision(17);
  s << value;
  return s.str();
}

}  // namespace stagger::meshgen
