// Howell & Ball's incompressible rigid-plastic shell and its spherical analogue (Verney): energy
// balance, incompressibility, stop.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "stagger/verify.hpp"

namespace {

using stagger::HowellBallShell;

TEST(HowellBallShell, KineticEnergyBecomesPlasticWorkAlongTheTrajectory) {
  const HowellBallShell shell;
  const double k0 = std::numbers::pi * 1845.0 * std::pow(0.08 * 417.1, 2) * std::log(0.1 / 0.08);
  EXPECT_NEAR(shell.kinetic_energy(0), k0, 1e-12 * k0);
  // Simpson's rule on the dissipation rate up to a few times, against the kinetic energy lost.
  for (const double t_end : {20e-6, 80e-6, 0.999 * shell.stopping_time()}) {
    const int n = 2000;
    const double h = t_end / n;
    double work = 0;
    for (int i = 0; i <= n; ++i) {
      const double weight = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
      work += weight * shell.dissipation_rate(i * h);
    }
    work *= h / 3.0;
    EXPECT_NEAR(k0 - shell.kinetic_energy(t_end), work, 1e-6 * k0) << "t = " << t_end;
  }
}

TEST(HowellBallShell, InnerVelocityIsTheDerivativeOfTheRadius) {
  const HowellBallShell shell;
  for (const double t : {1e-6, 40e-6, 100e-6}) {
    const double h = 1e-9;
    const double slope = (shell.inner_radius(t + h) - shell.inner_radius(t - h)) / (2 * h);
    EXPECT_NEAR(slope, shell.inner_velocity(t), 1e-5 * 417.1) << "t = " << t;
  }
  EXPECT_NEAR(shell.inner_velocity(0), -417.1, 1e-9);
}

TEST(HowellBallShell, ShellAreaIsConserved) {
  const HowellBallShell shell;
  const double area = 0.1 * 0.1 - 0.08 * 0.08;
  for (const double t : {0.0, 30e-6, 90e-6, 200e-6}) {
    const double ri = shell.inner_radius(t), ro = shell.outer_radius(t);
    EXPECT_NEAR(ro * ro - ri * ri, area, 1e-15) << "t = " << t;
  }
}

TEST(HowellBallShell, StopsNearThePrototypeRadii) {
  const HowellBallShell shell;
  // The compressible elastic-plastic scheme stops at 49.958 / 78.080 mm at 130 us (the prototype's
  // figures, docs/algorithm.md §16.2, which this code reproduces: docs/verification.md §8). The
  // incompressible rigid-plastic analytic model differs from them by its model error (0.04 mm);
  // 1 mm bounds that and catches a wrong analytic solution.
  std::printf("[ numbers  ] stopping radii %.6f %.6f mm at %.6f us\n", 1e3 * shell.inner_stopping_radius(),
              1e3 * shell.outer_stopping_radius(), 1e6 * shell.stopping_time());
  EXPECT_NEAR(shell.inner_stopping_radius(), 0.049958, 1e-3);
  EXPECT_NEAR(shell.outer_stopping_radius(), 0.078080, 1e-3);
  EXPECT_GT(shell.stopping_time(), 100e-6);
  EXPECT_LT(shell.stopping_time(), 130e-6);
  EXPECT_EQ(shell.inner_radius(130e-6), shell.inner_stopping_radius());
  EXPECT_EQ(shell.kinetic_energy(shell.stopping_time()), 0.0);
  // Monotone collapse up to the stop.
  double previous = shell.inner_radius(0);
  for (int i = 1; i <= 50; ++i) {
    const double r = shell.inner_radius(i * shell.stopping_time() / 50);
    EXPECT_LT(r, previous);
    previous = r;
  }
}

stagger::ShellParameters verney() {
  stagger::ShellParameters p;
  p.spherical = true;
  return p;
}

TEST(VerneyShell, KineticEnergyBecomesPlasticWorkAlongTheTrajectory) {
  const HowellBallShell shell(verney());
  // 2 pi rho (Ri^2 V0)^2 (1/Ri - 1/Ro): the full sphere (docs/derivations.md eq. 2.6).
  const double k0 = 2 * std::numbers::pi * 1845.0 * std::pow(0.08 * 0.08 * 417.1, 2) * (1 / 0.08 - 1 / 0.1);
  EXPECT_NEAR(shell.kinetic_energy(0), k0, 1e-12 * k0);
  for (const double t_end : {20e-6, 60e-6, 0.999 * shell.stopping_time()}) {
    const int n = 2000;
    const double h = t_end / n;
    double work = 0;
    for (int i = 0; i <= n; ++i) {
      const double weight = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
      work += weight * shell.dissipation_rate(i * h);
    }
    work *= h / 3.0;
    EXPECT_NEAR(k0 - shell.kinetic_energy(t_end), work, 1e-6 * k0) << "t = " << t_end;
  }
}

TEST(VerneyShell, InnerVelocityIsTheDerivativeOfTheRadius) {
  const HowellBallShell shell(verney());
  for (const double t : {1e-6, 40e-6, 80e-6}) {
    const double h = 1e-9;
    const double slope = (shell.inner_radius(t + h) - shell.inner_radius(t - h)) / (2 * h);
    EXPECT_NEAR(slope, shell.inner_velocity(t), 1e-5 * 417.1) << "t = " << t;
  }
  EXPECT_NEAR(shell.inner_velocity(0), -417.1, 1e-9);
}

TEST(VerneyShell, ShellVolumeIsConservedAndTheCollapseStops) {
  const HowellBallShell shell(verney());
  const double volume = 0.1 * 0.1 * 0.1 - 0.08 * 0.08 * 0.08;
  for (const double t : {0.0, 30e-6, 90e-6, 200e-6}) {
    const double ri = shell.inner_radius(t), ro = shell.outer_radius(t);
    EXPECT_NEAR(ro * ro * ro - ri * ri * ri, volume, 1e-16) << "t = " << t;
  }
  std::printf("[ numbers  ] Verney stopping radii %.6f %.6f mm at %.6f us\n", 1e3 * shell.inner_stopping_radius(),
              1e3 * shell.outer_stopping_radius(), 1e6 * shell.stopping_time());
  // The same shell stops later and further out than the cylinder: the converging sphere takes
  // more plastic work per unit of inward motion (2 Y |Q| / r^3 against (2 / sqrt 3) Y |Q| / r^2).
  const HowellBallShell cylinder;
  EXPECT_GT(shell.inner_stopping_radius(), cylinder.inner_stopping_radius() + 0.005);
  EXPECT_LT(shell.inner_stopping_radius(), 0.08);
  EXPECT_NEAR(shell.inner_radius(shell.stopping_time() + 1e-6), shell.inner_stopping_radius(), 1e-15);
  EXPECT_EQ(shell.kinetic_energy(shell.stopping_time()), 0.0);
  double previous = shell.inner_radius(0);
  for (int i = 1; i <= 50; ++i) {
    const double r = shell.inner_radius(i * shell.stopping_time() / 50);
    EXPECT_LT(r, previous);
    previous = r;
  }
}

}  // namespace
