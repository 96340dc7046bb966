// The pointwise physics kernels alone: equations of state against their formulas (the sound
// speed against a numerical derivative of the pressure), the radial return, the burn
// fraction (docs/algorithm.md §3, §7, §8).
#include <gtest/gtest.h>

#include <cmath>

#include "eos/eos_kernels.hpp"
#include "hydro/kernels/burn.hpp"
#include "hydro/kernels/strength.hpp"

namespace stagger {

namespace {

// c^2 = dp/drho|_e + (p / rho^2) dp/de|_rho by central differences of the EOS's own pressure
// (all three are linear in e, so the e step only needs to be large against round-off).
template <class Eos>
double numerical_c2(const Eos& eos, double rho, double e) {
  auto p = [&](double r, double en) {
    eos::PressureSound ps{};
    EXPECT_TRUE(eos::evaluate(eos, r, en, ps));
    return ps.p;
  };
  const double hr = 1e-6 * rho, he = 1e-3 * std::max(std::abs(e), 1e4);
  const double dp_drho = (p(rho + hr, e) - p(rho - hr, e)) / (2 * hr);
  const double dp_de = (p(rho, e + he) - p(rho, e - he)) / (2 * he);
  return dp_drho + p(rho, e) / (rho * rho) * dp_de;
}

double von_mises(const Deviator& s) {
  const double szz = -(s.xx + s.yy);
  return std::sqrt(1.5 * (s.xx * s.xx + s.yy * s.yy + szz * szz + 2 * s.xy * s.xy));
}

}  // namespace

TEST(EosKernels, IdealGas) {
  const IdealGas g{1.4};
  eos::PressureSound ps{};
  ASSERT_TRUE(eos::evaluate(g, 2.5, 3.0, ps));
  EXPECT_DOUBLE_EQ(ps.p, 0.4 * 2.5 * 3.0);
  EXPECT_DOUBLE_EQ(ps.c2, 1.4 * ps.p / 2.5);  // gamma p / rho
  EXPECT_NEAR(ps.c2, numerical_c2(g, 2.5, 3.0), 1e-8 * ps.c2);
  EXPECT_FALSE(eos::evaluate(g, -1.0, 3.0, ps));  // negative density: outside the domain
}

TEST(EosKernels, StiffenedGasWater) {
  // Water of the water-air shock tube: gamma 4.4, p_inf 6e8 Pa, at rho 1000 and p 1e9 Pa.
  const StiffenedGas g{4.4, 6e8};
  const double rho = 1000, p = 1e9;
  const double e = (p + 4.4 * 6e8) / (3.4 * rho);  // inverted by hand: e = (p + gamma p_inf) / ((gamma - 1) rho)
  eos::PressureSound ps{};
  ASSERT_TRUE(eos::evaluate(g, rho, e, ps));
  EXPECT_NEAR(ps.p, p, 1e-15 * 4.4 * 6e8 * 4);
  EXPECT_NEAR(ps.c2, 4.4 * (p + 6e8) / rho, 1e-14 * ps.c2);  // gamma (p + p_inf) / rho
  EXPECT_NEAR(ps.c2, numerical_c2(g, rho, e), 1e-7 * ps.c2);
  // p_inf = 0 is the ideal gas, bit for bit.
  eos::PressureSound gas{};
  ASSERT_TRUE(eos::evaluate(StiffenedGas{1.4, 0.0}, 2.5, 3.0, ps));
  ASSERT_TRUE(eos::evaluate(IdealGas{1.4}, 2.5, 3.0, gas));
  EXPECT_EQ(ps.p, gas.p);
  // Tension down to -p_inf is inside the domain; beyond it c^2 < 0 and the state is outside.
  EXPECT_TRUE(eos::evaluate(g, rho, (-0.5e8 + 4.4 * 6e8) / (3.4 * rho), ps));
  EXPECT_FALSE(eos::evaluate(g, rho, (-7e8 + 4.4 * 6e8) / (3.4 * rho), ps));
  EXPECT_FALSE(eos::evaluate(g, -1.0, e, ps));
}

TEST(EosKernels, MieGruneisenOnAndOffTheHugoniot) {
  // Copper-like constants.
  MieGruneisen m;
  m.rho0 = 8930, m.a0 = 3940, m.gamma0 = 2.0, m.s = 1.49;
  for (double rho : {8000.0, 8930.0, 10500.0}) {
    for (double e : {0.0, 2e5}) {
      // p = p_H(eta) + Gamma0 rho0 (e - e_H), with the Hugoniot p_H = rho0 c0^2 eta / (1 - s eta)^2
      // and its energy e_H = p_H (1/rho0 - 1/rho) / 2 = p_H eta / (2 rho0) (Rankine-Hugoniot).
      const double eta = 1 - m.rho0 / rho;
      const double pH = m.rho0 * m.a0 * m.a0 * eta / ((1 - m.s * eta) * (1 - m.s * eta));
      const double eH = 0.5 * pH * eta / m.rho0;
      const double expected = pH + m.gamma0 * m.rho0 * (e - eH);
      eos::PressureSound ps{};
      ASSERT_TRUE(eos::evaluate(m, rho, e, ps));
      EXPECT_NEAR(ps.p, expected, 1e-9 * std::max(std::abs(expected), m.rho0 * m.a0 * m.a0 * 1e-6)) << rho << " " << e;
      EXPECT_NEAR(ps.c2, numerical_c2(m, rho, e), 1e-6 * ps.c2) << rho << " " << e;
    }
  }
  // At the reference state the sound speed is the bulk sound speed.
  eos::PressureSound ps{};
  ASSERT_TRUE(eos::evaluate(m, m.rho0, 0.0, ps));
  EXPECT_NEAR(std::sqrt(ps.c2), m.a0, 1e-9 * m.a0);
  // Beyond the Hugoniot's singularity 1 - s eta = 0 (rho = rho0 s / (s - 1)): outside.
  EXPECT_FALSE(eos::evaluate(m, 1.01 * m.rho0 * m.s / (m.s - 1), 0.0, ps));
}

TEST(EosKernels, Jwl) {
  // TNT-like products.
  Jwl j;
  j.A = 3.712e11, j.B = 3.231e9, j.R1 = 4.15, j.R2 = 0.95, j.omega = 0.3, j.rho0 = 1630;
  for (double rho : {400.0, 1630.0, 2200.0}) {
    const double e = 4e6;
    // p = A (1 - omega/(R1 V)) exp(-R1 V) + B (1 - omega/(R2 V)) exp(-R2 V) + omega rho e, V = rho0/rho.
    const double V = j.rho0 / rho;
    const double expected = j.A * (1 - j.omega / (j.R1 * V)) * std::exp(-j.R1 * V) +
                            j.B * (1 - j.omega / (j.R2 * V)) * std::exp(-j.R2 * V) + j.omega * rho * e;
    eos::PressureSound ps{};
    ASSERT_TRUE(eos::evaluate(j, rho, e, ps));
    EXPECT_NEAR(ps.p, expected, 1e-12 * std::abs(expected)) << rho;
    EXPECT_NEAR(ps.c2, numerical_c2(j, rho, e), 1e-6 * ps.c2) << rho;
  }
}

TEST(StrengthKernels, RadialReturnLandsOnTheYieldSurface) {
  const double mu = 5e10, Y = 3e8;
  const Deviator trial{2e8, -1.5e8, 2.2e8};
  const double seq = von_mises(trial);
  ASSERT_GT(seq, Y);
  Deviator s = trial;
  const double dp = radial_return(Y, 0.0, 0.0, mu, s);
  EXPECT_NEAR(von_mises(s), Y, 1e-15 * Y * 4);
  // Radial: the same direction, scaled by Y / sigma_eq.
  EXPECT_NEAR(s.xx, trial.xx * Y / seq, 1e-6);
  EXPECT_NEAR(s.yy, trial.yy * Y / seq, 1e-6);
  EXPECT_NEAR(s.xy, trial.xy * Y / seq, 1e-6);
  EXPECT_DOUBLE_EQ(dp, (seq - Y) / (3 * mu));
  // Inside the surface: untouched, no plastic strain.
  Deviator inside{0.5 * trial.xx * Y / seq, 0.5 * trial.yy * Y / seq, 0.5 * trial.xy * Y / seq};
  const Deviator before = inside;
  EXPECT_EQ(radial_return(Y, 0.0, 0.0, mu, inside), 0.0);
  EXPECT_EQ(inside.xx, before.xx);
  EXPECT_EQ(inside.yy, before.yy);
  EXPECT_EQ(inside.xy, before.xy);
}

TEST(StrengthKernels, HardeningReturnLandsOnTheHardenedSurface) {
  // Y = Y0 + H eps_p: from eps_p^n the return lands on Y0 + H (eps_p^n + d) with
  // d = (sigma_eq - Y0 - H eps_p^n) / (3 mu + H), radially.
  const double mu = 5e10, Y0 = 3e8, H = 2e9, eps0 = 0.01;
  const Deviator trial{2e8, -1.5e8, 2.2e8};
  const double seq = von_mises(trial), Yn = Y0 + H * eps0;
  ASSERT_GT(seq, Yn);
  Deviator s = trial;
  const double d = radial_return(Y0, H, eps0, mu, s);
  EXPECT_NEAR(d, (seq - Yn) / (3 * mu + H), 1e-15 * d * 4);
  EXPECT_NEAR(von_mises(s), Y0 + H * (eps0 + d), 4e-16 * seq * 4);
  // The consistency condition: the trial norm less the elastic relaxation 3 mu d.
  EXPECT_NEAR(von_mises(s), seq - 3 * mu * d, 4e-16 * seq * 4);
  EXPECT_NEAR(s.xy / s.xx, trial.xy / trial.xx, 1e-14);
  EXPECT_NEAR(s.yy / s.xx, trial.yy / trial.xx, 1e-14);
  // Hardened enough, the same trial stress is elastic.
  Deviator inside = trial;
  EXPECT_EQ(radial_return(Y0, H, (seq - Y0) / H * 1.001, mu, inside), 0.0);
  EXPECT_EQ(inside.xx, trial.xx);
  // H = 0 is bitwise the perfectly plastic return whatever eps_p.
  Deviator a = trial, b = trial;
  EXPECT_EQ(radial_return(Y0, 0.0, 0.37, mu, a), radial_return(Y0, 0.0, 0.0, mu, b));
  EXPECT_EQ(a.xx, b.xx);
  EXPECT_EQ(a.yy, b.yy);
  EXPECT_EQ(a.xy, b.xy);
}

TEST(StrengthKernels, ElasticRateOfAUniaxialStrain) {
  // L = diag(d, 0): dS/dt = 2 mu (D - tr D / 3 I) = mu d (4/3, -2/3) and, with no spin, both
  // update forms agree.
  const double mu = 2.0, d = 0.3, h = 0.01;
  const VelocityGradient L{d, 0, 0, 0};
  for (bool objective : {false, true}) {
    const Deviator s = advance_stress(objective, mu, Deviator{}, Deviator{}, L, h);
    EXPECT_NEAR(s.xx, h * mu * d * 4.0 / 3.0, 1e-15);
    EXPECT_NEAR(s.yy, -h * mu * d * 2.0 / 3.0, 1e-15);
    EXPECT_EQ(s.xy, 0.0);
  }
}

TEST(BurnKernel, ProgrammedBurnFraction) {
  BurnModel b;
  b.detonation_speed = 7000;
  const double t_l = 1e-6, L = 1e-3;
  EXPECT_EQ(burn_fraction(0, 0.5e-6, t_l, L, b, 1.0), 0.0);  // not lit yet
  EXPECT_NEAR(burn_fraction(0, t_l + 0.1 * L / b.detonation_speed, t_l, L, b, 1.0), 0.1, 1e-14);
  EXPECT_EQ(burn_fraction(0, 1.0, t_l, L, b, 1.0), 1.0);    // clamped
  EXPECT_EQ(burn_fraction(0.4, t_l, t_l, L, b, 1.0), 0.4);  // never decreases
  // Beta burn: compression to V (relative volume) gives (1 - V) / (1 - V_CJ).
  b.beta_burn = true, b.cj_relative_volume = 0.75, b.rho0 = 1.0;
  EXPECT_DOUBLE_EQ(burn_fraction(0, 0, t_l, L, b, 1.0 / 0.875), 0.5);
}

}  // namespace stagger
