// The paper's smooth manufactured solution: the source balances the stress divergence.
#include <gtest/gtest.h>

#include <cmath>

#include "stagger/verify.hpp"

namespace {

using stagger::AccuracySolution;

TEST(AccuracySolution, MomentumSourceCancelsTheStressDivergence) {
  const AccuracySolution solution;
  const double h = 1e-6;
  // sigma = S - p I; b = -div sigma, by central differences.
  auto sxx = [&](double x, double y, double t) { return solution.stress_xx(x, y, t) - solution.pressure(x, y, t); };
  auto syy = [&](double x, double y, double t) { return solution.stress_yy(x, y, t) - solution.pressure(x, y, t); };
  auto sxy = [&](double x, double y, double t) { return solution.stress_xy(x, y, t); };
  for (const auto& [x, y, t] : {std::array{0.1, 0.2, 0.0}, std::array{0.37, 0.81, 3e-5}, std::array{0.9, 0.05, 1e-4}}) {
    const double div_x =
        (sxx(x + h, y, t) - sxx(x - h, y, t)) / (2 * h) + (sxy(x, y + h, t) - sxy(x, y - h, t)) / (2 * h);
    const double div_y =
        (sxy(x + h, y, t) - sxy(x - h, y, t)) / (2 * h) + (syy(x, y + h, t) - syy(x, y - h, t)) / (2 * h);
    const auto b = solution.momentum_source(x, y, t);
    const double scale = std::hypot(div_x, div_y);
    EXPECT_GT(scale, 1e8);  // pressure gradient of order rho0 a0^2 * 0.1 * 2 pi
    EXPECT_NEAR(b[0], -div_x, 1e-6 * scale);
    EXPECT_NEAR(b[1], -div_y, 1e-6 * scale);
  }
}

TEST(AccuracySolution, FieldsReturnAfterOnePeriodOfTheTranslation) {
  const AccuracySolution solution;
  const double period = 1.0 / 1e4;
  for (const auto& [x, y] : {std::array{0.13, 0.77}, std::array{0.5, 0.25}}) {
    EXPECT_NEAR(solution.density(x, y, period), solution.density(x, y, 0), 1e-9);
    EXPECT_NEAR(solution.stress_xx(x, y, period), solution.stress_xx(x, y, 0), 1e-3);
    EXPECT_NEAR(solution.stress_xy(x, y, period), solution.stress_xy(x, y, 0), 1e-3);
    // A quarter period later the pattern has moved.
    EXPECT_GT(std::abs(solution.density(x, y, period / 4) - solution.density(x, y, 0)), 1.0);
  }
}

TEST(AccuracySolution, InitialDataMatchThePaper) {
  const AccuracySolution solution;
  // rho0 (1 - 0.1 sin 0 - 0.1 cos 0) = 0.9 rho0; S_xx = s1 (1 - 0), S_yy = -s1 (0 - 1), S_xy = 2 s1.
  EXPECT_NEAR(solution.density(0, 0, 0), 0.9 * 8930, 1e-9);
  EXPECT_NEAR(solution.stress_xx(0, 0, 0), 60e6, 1e-6);
  EXPECT_NEAR(solution.stress_yy(0, 0, 0), 60e6, 1e-6);
  EXPECT_NEAR(solution.stress_xy(0, 0, 0), 120e6, 1e-6);
  EXPECT_LT(solution.pressure(0, 0, 0), 0.0);  // expanded below rho0: tension
  const auto sources = stagger::accuracy_sources();
  const auto b = sources.momentum(0.3, 0.4, 2e-5);
  EXPECT_EQ(b, solution.momentum_source(0.3, 0.4, 2e-5));
  EXPECT_EQ(sources.energy(0.3, 0.4, 2e-5), 0.0);
}

}  // namespace
