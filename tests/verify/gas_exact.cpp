// Exact gas solutions (lib/src/verify/gas_*.cpp): literature values and conservation checks.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>

#include "stagger/error.hpp"
#include "stagger/verify.hpp"

namespace {

using stagger::GasState;

/// Composite 5-point Gauss-Legendre of f over [a, b] in n panels.
double integrate(const std::function<double(double)>& f, double a, double b, int n) {
  static const double nodes[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                                  0.9061798459386640};
  static const double weights[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                                    0.2369268850561891};
  double sum = 0;
  const double h = (b - a) / n;
  for (int k = 0; k < n; ++k) {
    const double mid = a + (k + 0.5) * h;
    for (int q = 0; q < 5; ++q) sum += 0.5 * h * weights[q] * f(mid + 0.5 * h * nodes[q]);
  }
  return sum;
}

/// Integral over [0, 1] of f(sample(x, t)) split at the wave edges, where the exact
/// solution is smooth (the fan profile is a polynomial of degree 2/(gamma-1) = 5 in x).
double integrate_riemann(const stagger::ExactRiemann& exact, double t,
                         const std::function<double(const GasState&)>& f) {
  const auto waves = exact.wave_positions(t);
  double sum = 0, a = 0.0;
  for (int k = 0; k <= 5; ++k) {
    const double b = k < 5 ? waves[k] : 1.0;
    if (b > a) sum += integrate([&](double x) { return f(exact.sample(x, t)); }, a, b, 4);
    a = std::max(a, b);
  }
  return sum;
}

// Toro, "Riemann Solvers and Numerical Methods for Fluid Dynamics", 3rd ed., Table 4.2
// (gamma = 1.4): exact star pressure and velocity of his tests 1-4, and Table 4.3's star
// densities of test 1 (Sod).
TEST(ExactRiemann, ReproducesToroStarStates) {
  struct Case {
    GasState left, right;
    double p_star, u_star;
  };
  const Case cases[] = {
      {{1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, 0.30313, 0.92745},
      {{1.0, -2.0, 0.4}, {1.0, 2.0, 0.4}, 0.00189, 0.0},
      {{1.0, 0.0, 1000.0}, {1.0, 0.0, 0.01}, 460.894, 19.5975},
      {{5.99924, 19.5975, 460.894}, {5.99242, -6.19633, 46.0950}, 1691.64, 8.68975},
  };
  for (const Case& c : cases) {
    const stagger::ExactRiemann exact(c.left, c.right, 1.4);
    EXPECT_NEAR(exact.star_pressure(), c.p_star, 6e-6 * c.p_star + 5e-6);
    EXPECT_NEAR(exact.star_velocity(), c.u_star, 6e-6 * std::abs(c.u_star) + 5e-6);
  }
  const stagger::ExactRiemann sod({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, 1.4);
  EXPECT_NEAR(sod.star_density_left(), 0.42632, 5e-6);
  EXPECT_NEAR(sod.star_density_right(), 0.26557, 5e-6);
}

TEST(ExactRiemann, SodProfileConservesMassMomentumAndEnergy) {
  const double gamma = 1.4, t = 0.2;
  const stagger::ExactRiemann exact({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, gamma, 0.5);
  const double mass = integrate_riemann(exact, t, [](const GasState& s) { return s.density; });
  EXPECT_NEAR(mass, 0.5 * 1.0 + 0.5 * 0.125, 1e-10);
  // The waves stay inside [0, 1]: momentum grows by (p_L - p_R) t, energy is constant.
  const double momentum = integrate_riemann(exact, t, [](const GasState& s) { return s.density * s.velocity; });
  EXPECT_NEAR(momentum, (1.0 - 0.1) * t, 1e-10);
  const double energy = integrate_riemann(exact, t, [&](const GasState& s) {
    return 0.5 * s.density * s.velocity * s.velocity + s.pressure / (gamma - 1.0);
  });
  EXPECT_NEAR(energy, 0.5 * (1.0 + 0.1) / (gamma - 1.0), 1e-10);
}

TEST(ExactRiemann, ProfileIsContinuousAtTheFanEdges) {
  const stagger::ExactRiemann exact({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, 1.4, 0.5);
  const auto waves = exact.wave_positions(0.2);
  for (int k : {0, 1}) {
    const GasState before = exact.sample(waves[k] - 1e-10, 0.2), after = exact.sample(waves[k] + 1e-10, 0.2);
    EXPECT_NEAR(before.density, after.density, 1e-8);
    EXPECT_NEAR(before.velocity, after.velocity, 1e-8);
    EXPECT_NEAR(before.pressure, after.pressure, 1e-8);
  }
  // Across the contact only the density jumps; across the shock all three do.
  EXPECT_GT(exact.sample(waves[2] - 1e-9, 0.2).density - exact.sample(waves[2] + 1e-9, 0.2).density, 0.1);
  EXPECT_NEAR(exact.sample(waves[2] - 1e-9, 0.2).pressure, exact.sample(waves[2] + 1e-9, 0.2).pressure, 1e-12);
  EXPECT_NEAR(exact.sample(waves[4] + 1e-9, 0.2).density, 0.125, 1e-15);
}

TEST(ExactRiemann, RejectsVacuumAndBadStates) {
  EXPECT_THROW(stagger::ExactRiemann({1.0, -4.0, 0.4}, {1.0, 4.0, 0.4}, 1.4), stagger::Error);
  EXPECT_THROW(stagger::ExactRiemann({1.0, 0.0, -1.0}, {1.0, 0.0, 1.0}, 1.4), stagger::Error);
  EXPECT_THROW(stagger::ExactRiemann({1.0, 0.0, 1.0}, {1.0, 0.0, 1.0}, 1.0), stagger::Error);
}

// Rankine-Hugoniot in the frame of the Noh shock, D = u0 (gamma - 1)/2.
TEST(NohSolution, SatisfiesRankineHugoniotAtTheShock) {
  const double gamma = 5.0 / 3.0, t = 0.6;
  const stagger::NohSolution noh(gamma, 1.0, 1.0);
  const double radius = noh.shock_radius(t), speed = radius / t;
  EXPECT_NEAR(radius, 0.2, 1e-15);
  EXPECT_NEAR(noh.post_shock_density(), 16.0, 1e-12);
  const GasState ahead = noh.state(radius * (1 + 1e-12), t), behind = noh.state(radius * (1 - 1e-12), t);
  EXPECT_NEAR(ahead.density, 4.0, 1e-10);
  const double w1 = ahead.velocity - speed, w2 = behind.velocity - speed;
  const double mass1 = ahead.density * w1, mass2 = behind.density * w2;
  EXPECT_NEAR(mass1, mass2, 1e-10);
  EXPECT_NEAR(mass1 * w1 + ahead.pressure, mass2 * w2 + behind.pressure, 1e-10);
  auto enthalpy = [&](const GasState& s, double w) {
    return gamma / (gamma - 1.0) * s.pressure / s.density + 0.5 * w * w;
  };
  EXPECT_NEAR(enthalpy(ahead, w1), enthalpy(behind, w2), 1e-10);
  // Pre-shock compression by convergence: rho0 (1 + t/r) in 2D.
  EXPECT_NEAR(noh.state(0.5, t).density, 1.0 + 0.6 / 0.5, 1e-14);
}

// Kamm & Timmes (LA-UR-07-2849): alpha = 0.98407 (cylindrical) and
// 0.851072 (spherical: E = 0.851072 gives R = 1 at t = 1) for gamma = 1.4.
TEST(SedovSolution, AlphaMatchesTheLiterature) {
  EXPECT_NEAR(stagger::SedovSolution(1.4, 2).alpha(), 0.98407, 1e-4);
  EXPECT_NEAR(stagger::SedovSolution(1.4, 3).alpha(), 0.851072, 2e-6);
  // docs/verification.md §3: E_plane = 4 * 0.244816 gives R about 1.0 at t = 1.
  const stagger::SedovSolution sedov(1.4, 2, 1.0, 4 * 0.244816);
  EXPECT_NEAR(sedov.shock_radius(1.0), 1.0, 2e-3);
  EXPECT_NEAR(sedov.shock_radius(0.25), 0.5 * sedov.shock_radius(1.0), 1e-14);
}

TEST(SedovSolution, ProfileCarriesTheBlastEnergyAndPostShockState) {
  const double gamma = 1.4, energy = 2.5, rho0 = 1.3, t = 0.7;
  const stagger::SedovSolution sedov(gamma, 2, rho0, energy);
  const double radius = sedov.shock_radius(t);
  // Energy integral over the disc, in r (not in the similarity variable).
  const double total = integrate(
      [&](double r) {
        const GasState s = sedov.state(r, t);
        return (0.5 * s.density * s.velocity * s.velocity + s.pressure / (gamma - 1.0)) * 2.0 * std::numbers::pi * r;
      },
      0.0, radius, 400);
  EXPECT_NEAR(total / energy, 1.0, 1e-8);
  // Mass inside the shock = mass swept up.
  const double mass =
      integrate([&](double r) { return sedov.state(r, t).density * 2.0 * std::numbers::pi * r; }, 0.0, radius, 400);
  EXPECT_NEAR(mass / (rho0 * std::numbers::pi * radius * radius), 1.0, 1e-8);
  // Strong-shock jump just behind the front.
  const double speed = 0.5 * radius / t;
  const GasState behind = sedov.state(radius * (1 - 1e-12), t);
  EXPECT_NEAR(behind.density, rho0 * 6.0, 1e-8);
  EXPECT_NEAR(behind.velocity, 2.0 * speed / (gamma + 1.0), 1e-8);
  EXPECT_NEAR(behind.pressure, 2.0 * rho0 * speed * speed / (gamma + 1.0), 1e-8);
  EXPECT_EQ(sedov.state(radius * 1.001, t).density, rho0);
}

// Finite-difference residuals of the radial Euler equations (nu = 2) at interior points:
// checks the closed forms of Kamm & Timmes, not only their integral.
TEST(SedovSolution, ProfileSatisfiesTheEulerEquations) {
  const double gamma = 1.4;
  const stagger::SedovSolution sedov(gamma, 2, 1.0, 1.0);
  const double t = 1.0, radius = sedov.shock_radius(t), h = 1e-5;
  for (double lambda : {0.3, 0.6, 0.9}) {
    const double r = lambda * radius;
    auto s = [&](double rr, double tt) { return sedov.state(rr, tt); };
    const GasState c = s(r, t);
    const GasState rp = s(r + h, t), rm = s(r - h, t), tp = s(r, t + h), tm = s(r, t - h);
    auto d = [&](double plus, double minus) { return (plus - minus) / (2 * h); };
    const double continuity = d(tp.density, tm.density) + c.velocity * d(rp.density, rm.density) +
                              c.density * (d(rp.velocity, rm.velocity) + c.velocity / r);
    const double momentum = d(tp.velocity, tm.velocity) + c.velocity * d(rp.velocity, rm.velocity) +
                            d(rp.pressure, rm.pressure) / c.density;
    auto entropy = [&](const GasState& q) { return std::log(q.pressure) - gamma * std::log(q.density); };
    const double adiabatic = d(entropy(tp), entropy(tm)) + c.velocity * d(entropy(rp), entropy(rm));
    const double scale = c.density / t;  // rho / t sets the size of each term
    EXPECT_NEAR(continuity / scale, 0.0, 1e-6) << "lambda " << lambda;
    EXPECT_NEAR(momentum / (radius / (t * t)), 0.0, 1e-6) << "lambda " << lambda;
    EXPECT_NEAR(adiabatic * t, 0.0, 1e-6) << "lambda " << lambda;
  }
}

TEST(SedovSolution, RejectsTheVacuumCase) {
  EXPECT_THROW(stagger::SedovSolution(8.0, 3), stagger::Error);
  EXPECT_THROW(stagger::SedovSolution(1.4, 4), stagger::Error);
}

// The exact Taylor-Green fields satisfy the Euler equations with the energy source:
// div v = 0, v.grad v + grad p / rho = 0, v.grad e = s_e (steady), by central differences.
TEST(TaylorGreen, ExactFieldsSatisfyTheEquationsWithTheEnergySource) {
  const double gamma = 5.0 / 3.0, h = 1e-5;
  const auto sources = stagger::taylor_green_sources();
  ASSERT_TRUE(static_cast<bool>(sources.energy));
  EXPECT_FALSE(static_cast<bool>(sources.momentum));
  auto e = [&](double x, double y) { return stagger::taylor_green_pressure(x, y) / (gamma - 1.0); };
  double worst_div = 0, worst_momentum = 0, worst_energy = 0, largest_source = 0;
  for (double x : {0.1, 0.27, 0.5, 0.73, 0.9})
    for (double y : {0.05, 0.33, 0.61, 0.88}) {
      const auto v = stagger::taylor_green_velocity(x, y);
      const auto vxp = stagger::taylor_green_velocity(x + h, y), vxm = stagger::taylor_green_velocity(x - h, y);
      const auto vyp = stagger::taylor_green_velocity(x, y + h), vym = stagger::taylor_green_velocity(x, y - h);
      worst_div = std::max(worst_div, std::abs((vxp[0] - vxm[0] + vyp[1] - vym[1]) / (2 * h)));
      for (int i = 0; i < 2; ++i) {
        const double dpdx =
            (stagger::taylor_green_pressure(x + h, y) - stagger::taylor_green_pressure(x - h, y)) / (2 * h);
        const double dpdy =
            (stagger::taylor_green_pressure(x, y + h) - stagger::taylor_green_pressure(x, y - h)) / (2 * h);
        const double residual =
            v[0] * (vxp[i] - vxm[i]) / (2 * h) + v[1] * (vyp[i] - vym[i]) / (2 * h) + (i == 0 ? dpdx : dpdy);
        worst_momentum = std::max(worst_momentum, std::abs(residual));
      }
      const double advection =
          v[0] * (e(x + h, y) - e(x - h, y)) / (2 * h) + v[1] * (e(x, y + h) - e(x, y - h)) / (2 * h);
      const double source = sources.energy(x, y, 0.3);
      worst_energy = std::max(worst_energy, std::abs(advection - source));
      largest_source = std::max(largest_source, std::abs(source));
    }
  EXPECT_LT(worst_div, 1e-8);
  EXPECT_LT(worst_momentum, 1e-8);
  EXPECT_LT(worst_energy, 1e-8);
  EXPECT_GT(largest_source, 1.0);  // the check is not vacuous
}

}  // namespace
