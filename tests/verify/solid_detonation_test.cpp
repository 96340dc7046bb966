// Planar CJ detonation with its Taylor wave for the paper's Comp B JWL fit (cm-g-us, Mbar).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "stagger/verify.hpp"

namespace {

using stagger::CJDetonation;

const stagger::Jwl kJwl{5.242, 0.07678, 4.2, 1.1, 0.34, 1.712};
constexpr double kE0 = 0.085;  // Mbar cc/cc

// JWL p(V, E) and c^2(V, E), E = rho0 e, written out again from docs/algorithm.md §3.
double jwl_pressure(double v, double energy) {
  const auto& j = kJwl;
  return j.A * (1 - j.omega / (j.R1 * v)) * std::exp(-j.R1 * v) +
         j.B * (1 - j.omega / (j.R2 * v)) * std::exp(-j.R2 * v) + j.omega * energy / v;
}
double jwl_sound_speed_squared(double v, double energy) {
  // c^2 = dp/drho|_e + p / rho^2 dp/de|_rho by central differences in rho and e.
  const double rho = kJwl.rho0 / v, e = energy / kJwl.rho0;
  auto p = [](double r, double ee) { return jwl_pressure(kJwl.rho0 / r, kJwl.rho0 * ee); };
  const double hr = 1e-6 * rho, he = 1e-6 * e;
  const double dp_drho = (p(rho + hr, e) - p(rho - hr, e)) / (2 * hr);
  const double dp_de = (p(rho, e + he) - p(rho, e - he)) / (2 * he);
  return dp_drho + p(rho, e) / (rho * rho) * dp_de;
}

TEST(CJDetonation, RayleighLineIsTangentToTheHugoniot) {
  const CJDetonation cj;
  const double v = cj.cj_relative_volume(), d = cj.cj_speed();
  const double h = 1e-5;
  const double slope = (cj.hugoniot_pressure(v + h) - cj.hugoniot_pressure(v - h)) / (2 * h);
  EXPECT_NEAR(slope, -kJwl.rho0 * d * d, 1e-6 * kJwl.rho0 * d * d);
  EXPECT_NEAR(cj.cj_state().pressure, kJwl.rho0 * d * d * (1 - v), 1e-12);
  // D is the smallest speed whose Rayleigh line meets the Hugoniot.
  for (double w = 0.5; w < 0.99; w += 0.01)
    EXPECT_GE(cj.hugoniot_pressure(w) / (kJwl.rho0 * (1 - w)), d * d * (1 - 1e-12)) << "V = " << w;
  // The CJ state lies on the Hugoniot: E - E0 = p (1 - V) / 2 with the JWL pressure.
  const double energy = kE0 + 0.5 * cj.cj_state().pressure * (1 - v);
  EXPECT_NEAR(jwl_pressure(v, energy), cj.cj_state().pressure, 1e-12);
}

TEST(CJDetonation, FlowBehindTheFrontIsSonic) {
  const CJDetonation cj;
  const auto& s = cj.cj_state();
  const double energy = kE0 + 0.5 * s.pressure * (1 - cj.cj_relative_volume());
  const double c = std::sqrt(jwl_sound_speed_squared(cj.cj_relative_volume(), energy));
  EXPECT_NEAR(s.velocity + c, cj.cj_speed(), 1e-8);
  EXPECT_NEAR(s.velocity + s.sound_speed, cj.cj_speed(), 1e-12);
}

TEST(CJDetonation, ImpliedStateIsCloseToThePapersValues) {
  const CJDetonation cj;
  const auto& s = cj.cj_state();
  std::printf(
      "[ numbers  ] D %.6f cm/us, P_CJ %.6f Mbar, V_CJ %.6f, rho %.6f, u %.6f, c %.6f; plateau p %.6f "
      "rho %.6f c %.6f\n",
      cj.cj_speed(), s.pressure, cj.cj_relative_volume(), s.density, s.velocity, s.sound_speed, cj.plateau_pressure(),
      cj.plateau_state().density, cj.plateau_state().sound_speed);
  EXPECT_NEAR(cj.cj_speed(), 0.798, 0.003 * 0.798);           // 0.7991 implied
  EXPECT_NEAR(cj.cj_state().pressure, 0.295, 0.005 * 0.295);  // 0.2950 implied
}

TEST(CJDetonation, FitIsConsistentWithTheStandardDensity) {
  // The products' Hugoniot in (V, p) does not depend on rho0 (E0 is per volume), so only
  // D^2 = p / (rho0 (1 - V)) moves: rho0 = 1.717 (the standard Comp B fit) gives D = 0.798.
  stagger::DetonationParameters parameters;
  parameters.eos.rho0 = 1.717;
  const CJDetonation standard(parameters);
  const CJDetonation paper;
  EXPECT_NEAR(standard.cj_speed(), 0.798, 1e-4);
  EXPECT_NEAR(standard.cj_state().pressure, paper.cj_state().pressure, 1e-12);
  EXPECT_NEAR(paper.cj_speed(), 0.798 * std::sqrt(1.717 / 1.712), 1e-4);
}

TEST(CJDetonation, IsentropeIsTheJwlIsentropeThroughTheCjPoint) {
  const CJDetonation cj;
  EXPECT_NEAR(cj.isentrope_pressure(cj.cj_relative_volume()), cj.cj_state().pressure, 1e-14);
  // dE = -p dV along it: integrate E from the CJ point and compare p(V, E) with p_s(V).
  double v = cj.cj_relative_volume();
  double energy = kE0 + 0.5 * cj.cj_state().pressure * (1 - v);
  const double h = 1e-4;
  for (int i = 0; i < 5000; ++i) {  // to V = V_CJ + 0.5, Simpson steps
    energy -= h / 6 * (cj.isentrope_pressure(v) + 4 * cj.isentrope_pressure(v + h / 2) + cj.isentrope_pressure(v + h));
    v += h;
  }
  EXPECT_NEAR(jwl_pressure(v, energy), cj.isentrope_pressure(v), 1e-10);
  EXPECT_NEAR(cj.isentrope_sound_speed(v) * cj.isentrope_sound_speed(v), jwl_sound_speed_squared(v, energy), 1e-7);
}

TEST(CJDetonation, TaylorWaveJoinsTheCjFrontToTheRestingPlateau) {
  const CJDetonation cj;
  const double t = 1.0, d = cj.cj_speed();
  const auto front = cj.sample(d * t * (1 - 1e-12), t);
  EXPECT_NEAR(front.pressure, cj.cj_state().pressure, 1e-9);
  EXPECT_NEAR(front.velocity, cj.cj_state().velocity, 1e-9);
  EXPECT_NEAR(front.density, cj.cj_state().density, 1e-9);
  EXPECT_EQ(cj.sample(1.01 * d * t, t).pressure, 0.0);
  const auto rest = cj.sample(0.1 * d * t, t);
  EXPECT_EQ(rest.velocity, 0.0);
  EXPECT_NEAR(cj.isentrope_velocity(kJwl.rho0 / rest.density), 0.0, 1e-12);
  EXPECT_NEAR(cj.plateau_pressure(), cj.isentrope_pressure(kJwl.rho0 / rest.density), 1e-14);
  // Plateau edge is continuous.
  const double xp = cj.plateau_state().sound_speed * t;
  EXPECT_NEAR(cj.sample(xp * (1 + 1e-9), t).pressure, cj.plateau_pressure(), 1e-8);
}

TEST(CJDetonation, RiemannInvariantIsConstantAcrossTheFan) {
  const CJDetonation cj;
  const double t = 1.0;
  for (const double xi : {0.45, 0.55, 0.65, 0.75}) {
    const auto s = cj.sample(xi * t, t);
    const double v = kJwl.rho0 / s.density;
    // u + int_{V_CJ}^{V} c dV' / V' by the trapezoidal rule on a fine grid.
    const int n = 20000;
    const double a = cj.cj_relative_volume(), h = (v - a) / n;
    double integral = 0;
    for (int i = 0; i <= n; ++i) {
      const double w = a + i * h;
      integral += (i == 0 || i == n ? 0.5 : 1.0) * cj.isentrope_sound_speed(w) / w;
    }
    EXPECT_NEAR(s.velocity + integral * h, cj.cj_state().velocity, 1e-8) << "x/t = " << xi;
    EXPECT_NEAR(s.velocity + s.sound_speed, xi, 1e-12);
  }
}

TEST(CJDetonation, TaylorWaveSolvesTheEulerEquations) {
  const CJDetonation cj;
  for (const double x : {0.45, 0.6, 0.75}) {
    const double t = 1.0, h = 1e-5;
    auto s = [&](double xx, double tt) { return cj.sample(xx, tt); };
    const double rho_t = (s(x, t + h).density - s(x, t - h).density) / (2 * h);
    const double flux_x =
        (s(x + h, t).density * s(x + h, t).velocity - s(x - h, t).density * s(x - h, t).velocity) / (2 * h);
    EXPECT_NEAR(rho_t + flux_x, 0.0, 1e-6 * std::abs(rho_t)) << "mass at x = " << x;
    const auto c = s(x, t);
    const double u_t = (s(x, t + h).velocity - s(x, t - h).velocity) / (2 * h);
    const double u_x = (s(x + h, t).velocity - s(x - h, t).velocity) / (2 * h);
    const double p_x = (s(x + h, t).pressure - s(x - h, t).pressure) / (2 * h);
    EXPECT_NEAR(u_t + c.velocity * u_x + p_x / c.density, 0.0, 1e-6 * std::abs(u_t)) << "momentum at x = " << x;
  }
}

}  // namespace
