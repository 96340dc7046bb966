// The progress line's time to go (lib/src/driver/eta.hpp): exact for a constant dt, and within
// 10 % for a time step that shrinks steadily, where the average rate so far is off by a factor.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "driver/eta.hpp"

namespace stagger {
namespace {

// A run at one wall second per cycle whose dt follows `dt_of(t)`, sampled every 10 cycles: the
// ETA after `at` cycles, the true time to go to t_end and the average-rate answer.
struct Eta {
  double estimate, truth, naive;
};
template <class DtOf>
Eta eta_after(DtOf dt_of, int at, double t_end) {
  EtaEstimate eta;
  double t = 0;
  int cycle = 0;
  for (; cycle < at; ++cycle) {
    const double dt = dt_of(t);
    t += dt;
    if ((cycle + 1) % 10 == 0) eta.add(t, dt, cycle + 1, cycle + 1.0);
  }
  long to_go = 0;
  for (double u = t; u < t_end; u += dt_of(u)) ++to_go;
  return {eta.seconds_to(t_end), static_cast<double>(to_go), cycle * (t_end - t) / t};
}

}  // namespace

TEST(Eta, AConstantTimeStepGivesTheCyclesToGoTimesTheWallTimePerCycle) {
  const Eta e = eta_after([](double) { return 1e-3; }, 200, 0.5);
  std::printf("constant dt: estimate %.3f s, true %.3f s, average rate %.3f s\n", e.estimate, e.truth, e.naive);
  EXPECT_NEAR(e.estimate, e.truth, 1.0);  // one cycle of rounding in the count
}

TEST(Eta, AShrinkingTimeStepIsForeseenWhereTheAverageRateIsOptimistic) {
  // dt = 1e-3 exp(-t / 0.1): after 500 cycles to t_end = 0.5.
  const Eta e = eta_after([](double t) { return 1e-3 * std::exp(-t / 0.1); }, 500, 0.5);
  std::printf("dt decaying in t: estimate %.1f s, true %.1f s, average rate %.1f s\n", e.estimate, e.truth, e.naive);
  EXPECT_NEAR(e.estimate / e.truth, 1.0, 0.05);
  EXPECT_LT(e.naive, 0.5 * e.truth);  // the average rate so far: optimistic by more than 2x
  // dt falling towards zero at t = 0.5 (geometric per cycle, linear in t), off the model: still
  // much nearer than the average rate.
  const Eta f = eta_after([](double t) { return 1e-3 * (1 - 2 * t) + 1e-9; }, 500, 0.45);
  std::printf("dt falling to zero: estimate %.1f s, true %.1f s, average rate %.1f s\n", f.estimate, f.truth, f.naive);
  EXPECT_LT(std::abs(f.estimate - f.truth), 0.5 * std::abs(f.naive - f.truth));
}

TEST(Eta, NothingToSayBeforeTwoSamples) {
  EtaEstimate eta;
  EXPECT_LT(eta.seconds_to(1.0), 0.0);
  eta.add(0.1, 1e-3, 1, 0.5);
  EXPECT_LT(eta.seconds_to(1.0), 0.0);
}

}  // namespace stagger
