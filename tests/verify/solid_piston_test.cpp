// Exact solution of the copper elastic-plastic piston: jump conditions, yield, wave order.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "stagger/error.hpp"
#include "stagger/verify.hpp"

namespace {

using stagger::ElasticPlasticPiston;
using stagger::PistonParameters;
using stagger::SolidState;

// Mie-Grueneisen p(rho, e), written out again from docs/algorithm.md §3 (independent check).
double mg_pressure(const stagger::MieGruneisen& m, double rho, double e) {
  const double eta = 1.0 - m.rho0 / rho;
  const double strain = m.a0 * eta / (1.0 - m.s * eta);
  return m.rho0 * m.a0 * m.a0 * eta / std::pow(1.0 - m.s * eta, 2) + m.gamma0 * m.rho0 * (e - 0.5 * strain * strain);
}

// Residuals of mass, momentum and total energy across a shock of lab speed d (relative to the
// fluxes), with the normal stress P = p - S_xx.
void expect_jump_conditions(const SolidState& a, const SolidState& b, double d) {
  const double mass_a = a.density * (d - a.velocity), mass_b = b.density * (d - b.velocity);
  EXPECT_NEAR(mass_a, mass_b, 1e-10 * mass_a);
  const double pa = a.pressure - a.stress_xx, pb = b.pressure - b.stress_xx;
  EXPECT_NEAR(mass_a * (b.velocity - a.velocity), pb - pa, 1e-10 * pb);
  // Conservation form: m (E_b - E_a) = P_b u_b - P_a u_a, E = e + u^2 / 2.
  const double energy_flux =
      mass_a * ((b.energy + 0.5 * b.velocity * b.velocity) - (a.energy + 0.5 * a.velocity * a.velocity));
  EXPECT_NEAR(energy_flux, pb * b.velocity - pa * a.velocity, 1e-10 * pb * b.velocity);
}

TEST(ElasticPlasticPiston, JumpConditionsHoldAtBothWaves) {
  const ElasticPlasticPiston piston;
  expect_jump_conditions(piston.initial_state(), piston.elastic_state(), piston.elastic_wave_speed());
  expect_jump_conditions(piston.elastic_state(), piston.plastic_state(), piston.plastic_wave_speed());
  EXPECT_NEAR(piston.plastic_state().velocity, 20.0, 1e-10);
  for (const SolidState* s : {&piston.elastic_state(), &piston.plastic_state()})
    std::printf("[ numbers  ] rho %.6f u %.6f p %.6e S_xx %.6e e %.6f\n", s->density, s->velocity, s->pressure,
                s->stress_xx, s->energy);
  std::printf("[ numbers  ] elastic speed %.4f plastic speed %.4f m/s; at 150 us: %.6f %.6f m\n",
              piston.elastic_wave_speed(), piston.plastic_wave_speed(), piston.elastic_wave_speed() * 150e-6,
              piston.plastic_wave_speed() * 150e-6);
}

TEST(ElasticPlasticPiston, StatesObeyTheMieGruneisenEos) {
  const ElasticPlasticPiston piston;
  const auto& eos = piston.parameters().eos;
  for (const SolidState* s : {&piston.initial_state(), &piston.elastic_state(), &piston.plastic_state()})
    EXPECT_NEAR(s->pressure, mg_pressure(eos, s->density, s->energy), 1e-9 * std::abs(s->pressure));
  EXPECT_NEAR(piston.initial_state().energy, 5.5991, 1e-4);  // docs/algorithm.md §3.1
}

TEST(ElasticPlasticPiston, ShockedStatesSitOnTheYieldSurface) {
  const ElasticPlasticPiston piston;
  // With S_yy = S_zz = -S_xx / 2, sqrt(3/2 S:S) = 3/2 |S_xx| = Y: S_xx = -2Y/3 = -60 MPa.
  EXPECT_NEAR(piston.elastic_state().stress_xx, -60e6, 1e-6);
  EXPECT_NEAR(piston.plastic_state().stress_xx, -60e6, 1e-6);
  // The precursor reaches yield along the hypo-elastic path S_xx = (4 mu / 3) ln(rho0 / rho).
  const double rho1 = piston.elastic_state().density;
  EXPECT_NEAR(4.0 / 3.0 * 45e9 * std::log(8930.0 / rho1), -60e6, 1e-3);
}

TEST(ElasticPlasticPiston, PrecursorOutrunsThePlasticShockAndIsSupersonic) {
  const ElasticPlasticPiston piston;
  const double c_longitudinal = std::sqrt(3940.0 * 3940.0 + 4.0 / 3.0 * 45e9 / 8930.0);
  EXPECT_GT(piston.elastic_wave_speed(), c_longitudinal);         // Lax condition ahead
  EXPECT_LT(piston.elastic_wave_speed(), 1.01 * c_longitudinal);  // weak shock
  EXPECT_LT(piston.plastic_wave_speed(), piston.elastic_wave_speed());
  EXPECT_GT(piston.plastic_wave_speed(), piston.elastic_state().velocity);
  const double t = 150e-6;
  EXPECT_EQ(piston.sample(0.99 * piston.elastic_wave_speed() * t, t).density, piston.elastic_state().density);
  EXPECT_EQ(piston.sample(1.01 * piston.elastic_wave_speed() * t, t).density, piston.initial_state().density);
  EXPECT_EQ(piston.sample(0.99 * piston.plastic_wave_speed() * t, t).density, piston.plastic_state().density);
}

TEST(ElasticPlasticPiston, TooSlowPistonIsRejected) {
  PistonParameters parameters;
  parameters.piston_velocity = 1.0;  // below the elastic limit velocity (about 4.7 m/s)
  EXPECT_THROW(ElasticPlasticPiston{parameters}, stagger::Error);
}

}  // namespace
