/// @file gas_riemann.cpp
/// Exact ideal-gas Riemann solver after Toro, "Riemann Solvers and Numerical Methods for
/// Fluid Dynamics", 3rd ed., Springer 2009, chapter 4 (equation numbers below are Toro's).
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "stagger/error.hpp"
#include "stagger/verify.hpp"

namespace stagger {
namespace {

/// Toro eqs. (4.6)-(4.7): the pressure function f_K(p) of one side and its derivative.
struct PressureFunction {
  double value, derivative;
};

PressureFunction pressure_function(double p, const GasState& side, double sound_speed, double gamma) {
  if (p > side.pressure) {  // shock, eq. (4.21)
    const double a = 2.0 / ((gamma + 1.0) * side.density);
    const double b = (gamma - 1.0) / (gamma + 1.0) * side.pressure;
    const double root = std::sqrt(a / (p + b));
    return {(p - side.pressure) * root, root * (1.0 - 0.5 * (p - side.pressure) / (p + b))};
  }
  // rarefaction, eq. (4.26)
  const double ratio = p / side.pressure;
  const double exponent = (gamma - 1.0) / (2.0 * gamma);
  return {2.0 * sound_speed / (gamma - 1.0) * (std::pow(ratio, exponent) - 1.0),
          std::pow(ratio, -(gamma + 1.0) / (2.0 * gamma)) / (side.density * sound_speed)};
}

void check_state(const GasState& s, const char* which) {
  if (!(s.density > 0.0) || !(s.pressure > 0.0) || !std::isfinite(s.velocity)) {
    std::ostringstream message;
    message << "ExactRiemann: the " << which << " state (density " << s.density << ", velocity " << s.velocity
            << ", pressure " << s.pressure << ") needs a positive density and pressure and a finite velocity";
    throw Error(message.str());
  }
}

}  // namespace

ExactRiemann::ExactRiemann(GasState left, GasState right, double gamma, double x0)
    : left_(left), right_(right), gamma_(gamma), x0_(x0) {
  if (!(gamma > 1.0)) throw Error("ExactRiemann: gamma must be > 1, got " + std::to_string(gamma));
  check_state(left, "left");
  check_state(right, "right");
  c_left_ = std::sqrt(gamma * left.pressure / left.density);
  c_right_ = std::sqrt(gamma * right.pressure / right.density);
  const double du = right.velocity - left.velocity;
  // Pressure positivity condition, Toro eq. (4.40): otherwise the waves leave a vacuum.
  if (2.0 / (gamma - 1.0) * (c_left_ + c_right_) <= du) {
    std::ostringstream message;
    message << "ExactRiemann: the states separate too fast (u_R - u_L = " << du
            << " >= 2 (c_L + c_R)/(gamma - 1)): the solution contains a vacuum, which this solver "
               "does not handle";
    throw Error(message.str());
  }
  // Newton iteration on f(p) = f_L(p) + f_R(p) + du = 0 (Toro sec. 4.3.2), started from the
  // primitive-variable guess (eq. 4.47), floored at a small positive pressure.
  const double floor = 1e-14 * std::max(left.pressure, right.pressure);
  double p =
      0.5 * (left.pressure + right.pressure) - 0.125 * du * (left.density + right.density) * (c_left_ + c_right_);
  p = std::max(p, floor);
  bool converged = false;
  for (int iteration = 0; iteration < 200; ++iteration) {
    const PressureFunction fl = pressure_function(p, left, c_left_, gamma);
    const PressureFunction fr = pressure_function(p, right, c_right_, gamma);
    double next = p - (fl.value + fr.value + du) / (fl.derivative + fr.derivative);
    if (next < floor) next = 0.5 * (p + floor);  // stay in the domain of f
    const double change = std::abs(next - p) / (0.5 * (next + p));
    p = next;
    if (change < 1e-14) {
      converged = true;
      break;
    }
  }
  if (!converged) {
    // Round-off may keep the last digit oscillating: accept a negligible residual.
    const double residual =
        pressure_function(p, left, c_left_, gamma).value + pressure_function(p, right, c_right_, gamma).value + du;
    if (!(std::abs(residual) <= 1e-12 * (std::abs(du) + c_left_ + c_right_)))
      throw Error("ExactRiemann: the Newton iteration for the star pressure did not converge");
  }
  p_star_ = p;
  const PressureFunction fl = pressure_function(p, left, c_left_, gamma);
  const PressureFunction fr = pressure_function(p, right, c_right_, gamma);
  u_star_ = 0.5 * (left.velocity + right.velocity) + 0.5 * (fr.value - fl.value);  // eq. (4.9)
  const double g = (gamma - 1.0) / (gamma + 1.0);
  // Star densities: shock adiabat (eqs. 4.50, 4.57) or isentrope (eqs. 4.53, 4.60).
  auto star_density = [&](const GasState& s) {
    const double ratio = p_star_ / s.pressure;
    return ratio > 1.0 ? s.density * (ratio + g) / (g * ratio + 1.0) : s.density * std::pow(ratio, 1.0 / gamma);
  };
  rho_star_left_ = star_density(left);
  rho_star_right_ = star_density(right);
}

std::array<double, 5> ExactRiemann::wave_positions(double t) const {
  const double g = gamma_;
  std::array<double, 5> speeds{};
  if (p_star_ > left_.pressure) {  // left shock, eq. (4.52)
    const double s =
        left_.velocity - c_left_ * std::sqrt((g + 1.0) / (2.0 * g) * p_star_ / left_.pressure + (g - 1.0) / (2.0 * g));
    speeds[0] = speeds[1] = s;
  } else {  // left fan head and tail, eqs. (4.55)
    speeds[0] = left_.velocity - c_left_;
    speeds[1] = u_star_ - c_left_ * std::pow(p_star_ / left_.pressure, (g - 1.0) / (2.0 * g));
  }
  speeds[2] = u_star_;
  if (p_star_ > right_.pressure) {  // right shock, eq. (4.59)
    const double s = right_.velocity +
                     c_right_ * std::sqrt((g + 1.0) / (2.0 * g) * p_star_ / right_.pressure + (g - 1.0) / (2.0 * g));
    speeds[3] = speeds[4] = s;
  } else {  // right fan tail and head, eqs. (4.62)
    speeds[3] = u_star_ + c_right_ * std::pow(p_star_ / right_.pressure, (g - 1.0) / (2.0 * g));
    speeds[4] = right_.velocity + c_right_;
  }
  std::array<double, 5> positions{};
  for (int k = 0; k < 5; ++k) positions[k] = x0_ + speeds[k] * t;
  return positions;
}

GasState ExactRiemann::sample(double x, double t) const {
  if (!(t > 0.0)) return x < x0_ ? left_ : right_;
  const double g = gamma_;
  const double s = (x - x0_) / t;  // Toro sec. 4.5, Fig. 4.14
  const double exponent = (g - 1.0) / (2.0 * g);
  if (s <= u_star_) {  // left of the contact
    if (p_star_ > left_.pressure) {
      const double shock =
          left_.velocity - c_left_ * std::sqrt((g + 1.0) / (2.0 * g) * p_star_ / left_.pressure + exponent);
      if (s <= shock) return left_;
      return {rho_star_left_, u_star_, p_star_};
    }
    const double head = left_.velocity - c_left_;
    if (s <= head) return left_;
    const double tail = u_star_ - c_left_ * std::pow(p_star_ / left_.pressure, exponent);
    if (s > tail) return {rho_star_left_, u_star_, p_star_};
    // Inside the left fan, eq. (4.56).
    const double factor = 2.0 / (g + 1.0) + (g - 1.0) / ((g + 1.0) * c_left_) * (left_.velocity - s);
    return {left_.density * std::pow(factor, 2.0 / (g - 1.0)),
            2.0 / (g + 1.0) * (c_left_ + 0.5 * (g - 1.0) * left_.velocity + s),
            left_.pressure * std::pow(factor, 2.0 * g / (g - 1.0))};
  }
  if (p_star_ > right_.pressure) {
    const double shock =
        right_.velocity + c_right_ * std::sqrt((g + 1.0) / (2.0 * g) * p_star_ / right_.pressure + exponent);
    if (s >= shock) return right_;
    return {rho_star_right_, u_star_, p_star_};
  }
  const double head = right_.velocity + c_right_;
  if (s >= head) return right_;
  const double tail = u_star_ + c_right_ * std::pow(p_star_ / right_.pressure, exponent);
  if (s < tail) return {rho_star_right_, u_star_, p_star_};
  // Inside the right fan, eq. (4.63).
  const double factor = 2.0 / (g + 1.0) - (g - 1.0) / ((g + 1.0) * c_right_) * (right_.velocity - s);
  return {right_.density * std::pow(factor, 2.0 / (g - 1.0)),
          2.0 / (g + 1.0) * (-c_right_ + 0.5 * (g - 1.0) * right_.velocity + s),
          right_.pressure * std::pow(factor, 2.0 * g / (g - 1.0))};
}

}  // namespace stagger
