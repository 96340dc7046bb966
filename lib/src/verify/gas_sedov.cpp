/// @file gas_sedov.cpp
/// The Sedov-Taylor-von Neumann similarity solution for a point blast in a uniform ideal gas
/// (Sedov 1959, ch. IV), in the closed form of Kamm & Timmes, "On efficient generation of
/// numerically robust Sedov solutions", LA-UR-07-2849 (2007), uniform density (omega = 0),
/// standard case. Equation numbers below are Kamm & Timmes'.
///
/// Energy normalisation (derived here): with U = dR/dt = 2R/((nu+2)t) and the strong-shock
/// states u2 = 2U/(gamma+1), rho2 = rho0 (gamma+1)/(gamma-1), p2 = 2 rho0 U^2/(gamma+1),
/// the energy inside the shock is
///   E = sigma_nu R^nu int_0^1 [rho u^2/2 + p/(gamma-1)] lambda^(nu-1) dlambda
///     = alpha rho0 R^(nu+2) / t^2,  alpha = 8 sigma_nu I / ((nu+2)^2 (gamma^2 - 1)),
///   I = int_0^1 (g f^2 + h) lambda^(nu-1) dlambda,
/// with sigma_nu = 2, 2 pi, 4 pi and f, g, h the velocity, density and pressure ratios to
/// the post-shock values.
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <sstream>

#include "stagger/error.hpp"
#include "stagger/simulation.hpp"
#include "stagger/verify.hpp"

namespace stagger {

SedovSolution::SedovSolution(double gamma, int nu, double rho0, double energy)
    : gamma_(gamma), rho0_(rho0), energy_(energy), nu_(nu) {
  std::ostringstream problem;
  if (!(gamma > 1.0))
    problem << "gamma = " << gamma << " must be > 1";
  else if (nu < 1 || nu > 3)
    problem << "nu = " << nu << " must be 1 (planar), 2 (cylindrical) or 3 (spherical)";
  else if (!(rho0 > 0.0))
    problem << "rho0 = " << rho0 << " must be positive";
  else if (!(energy > 0.0))
    problem << "energy = " << energy << " must be positive";
  else if (std::abs(gamma - 2.0) < 1e-12)
    problem << "gamma = 2 is a singular case (Kamm & Timmes' omega3)";
  if (!problem.str().empty()) throw Error("SedovSolution: " + problem.str());

  const double j = nu, gm1 = gamma - 1.0, gp1 = gamma + 1.0;
  const double xg2 = j + 2.0;                  // j + 2 - omega
  const double v2 = 4.0 / (xg2 * gp1);         // eq. 18: V behind the shock
  const double vstar = 2.0 / (gm1 * j + 2.0);  // eq. 19: standard case if v2 < vstar
  if (!(v2 < vstar - 1e-12)) {
    std::ostringstream message;
    message << "SedovSolution: gamma = " << gamma << ", nu = " << nu
            << " is the singular or vacuum case of Kamm & Timmes, which is not implemented";
    throw Error(message.str());
  }
  const double denom2 = 2.0 * gm1 + j;      // 2(gamma-1) + j - gamma omega
  const double denom3 = j * (2.0 - gamma);  // j (2 - gamma) - omega
  // Exponents, eqs. 42-47.
  a0_ = 2.0 / xg2;
  a2_ = -gm1 / denom2;
  a1_ = xg2 * gamma / (2.0 + j * gm1) * (2.0 * j * (2.0 - gamma) / (gamma * xg2 * xg2) - a2_);
  a3_ = j / denom2;
  a4_ = xg2 * j * a1_ / denom3;
  a5_ = -2.0 * j / denom3;
  // Combinations, eqs. 33-37.
  A_ = 0.25 * xg2 * gp1;
  B_ = gp1 / gm1;
  C_ = 0.5 * xg2 * gamma;
  D_ = xg2 * gp1 / (xg2 * gp1 - 2.0 * (2.0 + j * gm1));
  E_ = 0.5 * (2.0 + j * gm1);
  w2_ = C_ * v2 - 1.0;  // the origin is at V = v0 = 1/C, i.e. w = 0

  // I = int_0^1 (g f^2 + h) lambda^(nu-1) dlambda by composite 5-point Gauss-Legendre in
  // lambda: the integrand is smooth in lambda (V is analytic in w ~ lambda^(1/|a2|)), while
  // in V it has an integrable singularity at the origin.
  constexpr double nodes[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640};
  constexpr double weights[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                                 0.2369268850561891};
  constexpr int panels = 400;
  double integral = 0;
  for (int k = 0; k < panels; ++k) {
    const double a = static_cast<double>(k) / panels, b = static_cast<double>(k + 1) / panels;
    for (int q = 0; q < 5; ++q) {
      const double lambda = 0.5 * (a + b) + 0.5 * (b - a) * nodes[q];
      const auto s = similarity(lambda);
      integral += 0.5 * (b - a) * weights[q] * (s[1] * s[0] * s[0] + s[2]) * std::pow(lambda, nu - 1);
    }
  }
  const double sigma = nu == 1 ? 2.0 : (nu == 2 ? 2.0 * std::numbers::pi : 4.0 * std::numbers::pi);
  alpha_ = 8.0 * sigma * integral / (xg2 * xg2 * (gamma * gamma - 1.0));
}

SedovSolution::Functions SedovSolution::functions_of_w(double w) const {
  // Eqs. 29-32 and 38-41 with omega = 0, V = (1 + w)/C.
  const double v = (1.0 + w) / C_;
  const double x1 = A_ * v, x2 = B_ * w, x3 = D_ * (1.0 - E_ * v), x4 = B_ * (1.0 - 0.5 * (nu_ + 2.0) * v);
  const double lambda = std::pow(x1, -a0_) * std::pow(x2, -a2_) * std::pow(x3, -a1_);
  return {lambda, x1 * lambda, std::pow(x2, a3_) * std::pow(x3, a4_) * std::pow(x4, a5_),
          std::pow(x1, a0_ * nu_) * std::pow(x3, a4_ - 2.0 * a1_) * std::pow(x4, 1.0 + a5_)};
}

double SedovSolution::w_of_lambda(double lambda) const {
  // lambda(w) rises monotonically from 0 (w = 0) to 1 (w = w2): bisection in log w, which
  // resolves the tiny w near the origin (w ~ lambda^(1/|a2|)).
  double lo = -700.0, hi = std::log(w2_);
  if (functions_of_w(std::exp(lo)).lambda >= lambda) return 0.0;
  for (int iteration = 0; iteration < 80 && hi - lo > 1e-15; ++iteration) {
    const double mid = 0.5 * (lo + hi);
    (functions_of_w(std::exp(mid)).lambda < lambda ? lo : hi) = mid;
  }
  return std::exp(0.5 * (lo + hi));
}

std::array<double, 3> SedovSolution::similarity(double lambda) const {
  if (lambda >= 1.0) return {1.0, 1.0, 1.0};
  const Functions s = functions_of_w(lambda <= 0.0 ? 0.0 : w_of_lambda(lambda));
  return {s.f, s.g, s.h};
}

double SedovSolution::shock_radius(double t) const {
  return std::pow(energy_ / (alpha_ * rho0_), 1.0 / (nu_ + 2.0)) * std::pow(t, 2.0 / (nu_ + 2.0));
}

double SedovSolution::post_shock_density() const {
  return rho0_ * (gamma_ + 1.0) / (gamma_ - 1.0);
}

GasState SedovSolution::state(double r, double t) const {
  const double radius = shock_radius(t);
  if (!(t > 0.0) || r >= radius) return {rho0_, 0.0, 0.0};
  const double speed = 2.0 * radius / ((nu_ + 2.0) * t);  // dR/dt
  const auto s = similarity(r / radius);
  return {post_shock_density() * s[1], 2.0 * speed / (gamma_ + 1.0) * s[0],
          2.0 * rho0_ * speed * speed / (gamma_ + 1.0) * s[2]};
}

Reference sedov_reference(double gamma, double rho0, double energy_quarter, int nu) {
  // The quarter holds 1/4 of the plane's energy (nu = 2); in rz (nu = 3) it is the energy per
  // radian of the half space z >= 0, 1/(4 pi) of the sphere's.
  const double total = nu == 3 ? 4.0 * M_PI * energy_quarter : 4.0 * energy_quarter;
  const auto solution = std::make_shared<const SedovSolution>(gamma, nu, rho0, total);
  return [solution, rho0](const Simulation& simulation, NamedValues& errors, NamedValues& diagnostics) {
    const double t = simulation.time();
    const auto density = simulation.density();
    zone_field_errors(
        simulation, density, [&](double x, double y) { return solution->state(std::hypot(x, y), t).density; },
        "density", errors);
    double peak = 0;
    for (double rho : density) peak = std::max(peak, rho);
    const FrontCrossing front =
        front_crossing(simulation.mesh(), simulation.x(), simulation.y(), density, 0.5 * (rho0 + peak),
                       [](double x, double y) { return std::hypot(x, y); });
    const double exact = solution->shock_radius(t);
    diagnostics.emplace_back("shock_radius", front.position);
    diagnostics.emplace_back("shock_radius_exact", exact);
    if (exact > 0 && front.crossings > 0)
      diagnostics.emplace_back("shock_radius_error", (front.position - exact) / exact);
    diagnostics.emplace_back("peak_density", peak);
    diagnostics.emplace_back("peak_density_exact", solution->post_shock_density());
  };
}

}  // namespace stagger
