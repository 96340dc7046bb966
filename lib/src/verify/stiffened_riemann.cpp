/// @file stiffened_riemann.cpp
/// Exact Riemann solver between two stiffened gases. With P = p + p_inf a stiffened gas obeys
/// the ideal-gas relations of Toro, "Riemann Solvers and Numerical Methods for Fluid Dynamics",
/// 3rd ed., Springer 2009, ch. 4 (equation numbers below are Toro's), with c^2 = gamma P / rho;
/// each side carries its own shift (Ivings, Causon and Toro 1998). The star pressure p* is
/// common to both sides, so each side's pressure function is evaluated at its own P* = p* + p_inf.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "stagger/error.hpp"
#include "stagger/verify.hpp"

namespace stagger {
namespace {

struct PressureFunction {
  double value, derivative;
};

/// Toro eqs. (4.6)-(4.7), (4.21), (4.26) in shifted pressures.
PressureFunction side_function(double p, const StiffenedSide& side, double c) {
  const double g = side.gamma, big_p = p + side.p_inf, big_pk = side.state.pressure + side.p_inf;
  if (p > side.state.pressure) {  // shock
    const double a = 2.0 / ((g + 1.0) * side.state.density);
    const double b = (g - 1.0) / (g + 1.0) * big_pk;
    const double root = std::sqrt(a / (big_p + b));
    return {(big_p - big_pk) * root, root * (1.0 - 0.5 * (big_p - big_pk) / (big_p + b))};
  }
  const double ratio = big_p / big_pk;  // rarefaction
  return {2.0 * c / (g - 1.0) * (std::pow(ratio, (g - 1.0) / (2.0 * g)) - 1.0),
          std::pow(ratio, -(g + 1.0) / (2.0 * g)) / (side.state.density * c)};
}

/// Star density behind the side's wave: shock adiabat (4.50) or isentrope (4.53) in P.
double star_density(double p_star, const StiffenedSide& side) {
  const double g = side.gamma, ratio = (p_star + side.p_inf) / (side.state.pressure + side.p_inf);
  const double h = (g - 1.0) / (g + 1.0);
  return ratio > 1.0 ? side.state.density * (ratio + h) / (h * ratio + 1.0)
                     : side.state.density * std::pow(ratio, 1.0 / g);
}

void check_side(const StiffenedSide& s, const char* which) {
  if (!(s.state.density > 0.0) || !(s.state.pressure + s.p_inf > 0.0) || !std::isfinite(s.state.velocity) ||
      !(s.gamma > 1.0) || !(s.p_inf >= 0.0)) {
    std::ostringstream message;
    message << "StiffenedRiemann: the " << which << " state (density " << s.state.density << ", pressure "
            << s.state.pressure << ", gamma " << s.gamma << ", p_inf " << s.p_inf
            << ") needs rho > 0, p + p_inf > 0, gamma > 1 and p_inf >= 0";
    throw Error(message.str());
  }
}

/// Sample one side (sign -1: left, +1: right) at speed s = (x - x0)/t, Toro sec. 4.5 with the
/// fans of eqs. (4.56) and (4.63) in shifted pressures.
GasState sample_side(const StiffenedSide& side, double c, double sign, double s, double p_star, double u_star,
                     double rho_star) {
  const double g = side.gamma, big_pk = side.state.pressure + side.p_inf, u = side.state.velocity;
  const double ratio = (p_star + side.p_inf) / big_pk;
  const GasState star{rho_star, u_star, p_star};
  if (ratio > 1.0) {
    const double shock = u + sign * c * std::sqrt((g + 1.0) / (2.0 * g) * ratio + (g - 1.0) / (2.0 * g));
    return sign * (s - shock) >= 0.0 ? side.state : star;
  }
  const double head = u + sign * c;
  const double tail = u_star + sign * c * std::pow(ratio, (g - 1.0) / (2.0 * g));
  if (sign * (s - head) >= 0.0) return side.state;
  if (sign * (s - tail) < 0.0) return star;
  const double factor = 2.0 / (g + 1.0) - sign * (g - 1.0) / ((g + 1.0) * c) * (u - s);
  return {side.state.density * std::pow(factor, 2.0 / (g - 1.0)),
          2.0 / (g + 1.0) * (-sign * c + 0.5 * (g - 1.0) * u + s),
          big_pk * std::pow(factor, 2.0 * g / (g - 1.0)) - side.p_inf};
}

}  // namespace

StiffenedRiemann::StiffenedRiemann(StiffenedSide left, StiffenedSide right, double x0) : side_{left, right}, x0_(x0) {
  check_side(left, "left");
  check_side(right, "right");
  for (int k = 0; k < 2; ++k)
    c_[k] = std::sqrt(side_[k].gamma * (side_[k].state.pressure + side_[k].p_inf) / side_[k].state.density);
  const double du = right.state.velocity - left.state.velocity;
  // Newton on f_L(p) + f_R(p) + du = 0 (Toro sec. 4.3.2); p* must keep both P* > 0.
  const double floor = -std::min(left.p_inf, right.p_inf) +
                       1e-14 * std::max(left.state.pressure + left.p_inf, right.state.pressure + right.p_inf);
  double p = std::max(0.5 * (left.state.pressure + right.state.pressure), floor);
  bool converged = false;
  for (int iteration = 0; iteration < 200 && !converged; ++iteration) {
    const PressureFunction fl = side_function(p, left, c_[0]), fr = side_function(p, right, c_[1]);
    double next = p - (fl.value + fr.value + du) / (fl.derivative + fr.derivative);
    if (next < floor) next = 0.5 * (p + floor);
    converged = std::abs(next - p) <= 1e-14 * (std::abs(next) + std::abs(p) + left.p_inf + right.p_inf);
    p = next;
  }
  const PressureFunction fl = side_function(p, left, c_[0]), fr = side_function(p, right, c_[1]);
  if (!converged && !(std::abs(fl.value + fr.value + du) <= 1e-12 * (std::abs(du) + c_[0] + c_[1])))
    throw Error("StiffenedRiemann: the Newton iteration for the star pressure did not converge (a vacuum?)");
  p_star_ = p;
  u_star_ = 0.5 * (left.state.velocity + right.state.velocity) + 0.5 * (fr.value - fl.value);  // eq. (4.9)
  for (int k = 0; k < 2; ++k) rho_star_[k] = star_density(p_star_, side_[k]);
}

GasState StiffenedRiemann::sample(double x, double t) const {
  if (!(t > 0.0)) return x < x0_ ? side_[0].state : side_[1].state;
  const double s = (x - x0_) / t;
  return s <= u_star_ ? sample_side(side_[0], c_[0], -1.0, s, p_star_, u_star_, rho_star_[0])
                      : sample_side(side_[1], c_[1], 1.0, s, p_star_, u_star_, rho_star_[1]);
}

}  // namespace stagger
