#include "expression.hpp"

#include <muParser.h>

#include <cmath>
#include <numbers>

namespace stagger::scene_detail {

struct Expression::State {
  mu::Parser parser;
  std::vector<double> variables;  // muparser keeps pointers into this: never resized
  std::string text;
};

namespace {
double power(double base, double exponent) {
  return std::pow(base, exponent);
}
}  // namespace

Expression::Expression(const std::string& text, const std::vector<std::string>& variables)
    : state_(std::make_shared<State>()) {
  state_->text = text;
  state_->variables.assign(variables.size(), 0.0);
  try {
    for (std::size_t i = 0; i < variables.size(); ++i) state_->parser.DefineVar(variables[i], &state_->variables[i]);
    state_->parser.DefineConst("pi", std::numbers::pi);
    state_->parser.DefineFun("pow", power);
    state_->parser.SetExpr(text);
    // muparser parses lazily: evaluate once so that syntax errors surface here.
    static_cast<void>(state_->parser.Eval());
  } catch (const mu::Parser::exception_type& error) {
    throw ExpressionError{error.GetMsg()};
  }
}

namespace {
double evaluate(mu::Parser& parser) {
  try {
    return parser.Eval();
  } catch (const mu::Parser::exception_type&) {
    return std::nan("");  // reported by the caller's finiteness check
  }
}
}  // namespace

double Expression::operator()(const std::vector<double>& values) const {
  for (std::size_t i = 0; i < values.size() && i < state_->variables.size(); ++i) state_->variables[i] = values[i];
  return evaluate(state_->parser);
}

double Expression::operator()(double a) const {
  if (!state_->variables.empty()) state_->variables[0] = a;
  return evaluate(state_->parser);
}

double Expression::operator()(double a, double b) const {
  if (!state_->variables.empty()) state_->variables[0] = a;
  if (state_->variables.size() > 1) state_->variables[1] = b;
  return evaluate(state_->parser);
}

const std::string& Expression::text() const {
  return state_->text;
}

SpaceFunction space_function(const Expression& expression) {
  return [expression](double x, double y) { return expression(x, y); };
}

TimeFunction time_function(const Expression& expression) {
  return [expression](double t) { return expression(t); };
}

}  // namespace stagger::scene_detail
