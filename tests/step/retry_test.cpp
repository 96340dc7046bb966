// A zone that folds at the half step is tangling, and the step is retried with a smaller dt
// (docs/algorithm.md §9): not an equation-of-state failure, although its half-step density
// mass / area is negative and the EOS rejects it too.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "stagger/error.hpp"
#include "stagger/simulation.hpp"
#include "support/gas_problem.hpp"

namespace stagger {

namespace {

// A cold ideal gas (e = 0: no pressure, no sound speed, no CFL limit) in the unit square
// about the origin, moving with the strain v = a (y, x), divergence-free at t = 0 (no
// volume-change limit on the first dt). With the viscosities off nothing acts on the points,
// which move ballistically, x(t) = (I + t L) x, so every zone's area scales by
// det(I + t L) = 1 - a^2 t^2. dt_max = 3/a makes the first try dt = 3/a, whose half-step
// geometry at t = 1.5/a has area -1.25 times the initial one.
Problem folding_problem(double a) {
  Problem p = testing::gas_problem(testing::rectangle_mesh(-0.5, 0.5, -0.5, 0.5, 2, 2, testing::unchecked()), 1.4,
                                   100 / a, "folding");
  RegionSetup r = testing::gas_region(constant_field(1.0));
  r.specific_internal_energy = constant_field(0.0);
  r.velocity_x = [a](double, double y) { return a * y; };
  r.velocity_y = [a](double x, double) { return a * x; };
  p.regions.push_back(r);
  p.options.q1 = p.options.q2 = 0;
  p.options.hourglass_coefficient = 0;
  p.options.max_retries = 8;
  p.options.dt_max = 3 / a;
  return p;
}

}  // namespace

TEST(Retry, HalfStepFoldIsRetriedNotAnEosFailure) {
  const double a = 1.0;
  Simulation sim(folding_problem(a));
  ASSERT_NO_THROW(sim.step());
  // Halvings from dt = 3/a: 1.5/a folds the end geometry (det = 1 - 2.25); 0.75/a is the
  // first that keeps every area positive.
  EXPECT_EQ(sim.dt(), 0.75 / a);
  EXPECT_EQ(sim.dt_limit(), "retry after a tangled step");
  EXPECT_EQ(sim.cycle(), 1);
  // The step taken is the linear motion: area 1 - (a dt)^2 of the whole square.
  double area = 0;
  for (double z : sim.zone_area()) area += z;
  EXPECT_NEAR(area, 1 - 0.75 * 0.75, 1e-14);
  for (double rho : sim.density()) EXPECT_GT(rho, 0);
}

TEST(Retry, ZeroAreaHalfStepLeavesNoNaNInTheRetry) {
  // dt = 2/a puts the half step at det = 0 exactly: density and pressure there are infinite
  // or NaN, and so are that attempt's corner forces. The retry evaluates the forces at t^n
  // afresh and must not carry them into e^n (0 * NaN is NaN): dt = 1/a then folds the end
  // geometry exactly (det = 0) and dt = 0.5/a is taken.
  Problem p = folding_problem(1.0);
  p.options.dt_max = 2.0;
  Simulation sim(std::move(p));
  ASSERT_NO_THROW(sim.step());
  EXPECT_EQ(sim.dt(), 0.5);
  for (double e : sim.specific_internal_energy()) EXPECT_EQ(e, 0.0);
}

TEST(Retry, TooFewRetriesReportTanglingNotTheEos) {
  Problem p = folding_problem(1.0);
  p.options.max_retries = 1;  // dt = 3 folds the half step, 1.5 the end geometry
  Simulation sim(std::move(p));
  try {
    sim.step();
    FAIL() << "expected the step to fail";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("tangled"), std::string::npos) << what;
    EXPECT_EQ(what.find("equation of state"), std::string::npos) << what;
  }
}

}  // namespace stagger
