#pragma once
// String expressions in scene files (muparser), compiled once and evaluated at set-up.
// A compiled expression owns its parser and its variables: a muparser object is not
// thread-safe, so each SpaceFunction/TimeFunction built here must be called from one
// thread at a time (the Simulation calls them during set-up only).
#include <memory>
#include <string>
#include <vector>

#include "stagger/problem.hpp"

namespace stagger::scene_detail {

/// An expression of named variables. Copies share the parser (cheap, not thread-safe).
class Expression {
 public:
  /// Compiles `text` over `variables` (e.g. {"x", "y"}); throws ExpressionError with
  /// muparser's message (what and where in the text) when it does not parse.
  Expression(const std::string& text, const std::vector<std::string>& variables);
  /// Evaluates with the variables set to `values` (same order as at construction).
  double operator()(const std::vector<double>& values) const;
  double operator()(double a) const;
  double operator()(double a, double b) const;
  const std::string& text() const;

 private:
  struct State;
  std::shared_ptr<State> state_;
};

/// Thrown by Expression for a text that does not parse; the caller adds file/line/key.
struct ExpressionError {
  std::string message;
};

SpaceFunction space_function(const Expression& expression);
TimeFunction time_function(const Expression& expression);

}  // namespace stagger::scene_detail
