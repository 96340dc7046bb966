// The exact accumulator behind the energy audit, momentum and work totals
// (hydro/exact_sum.hpp): order-independent to the last bit, and exact where a double sum is not.
#include "hydro/exact_sum.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace stagger {
namespace {

TEST(ExactSum, CancellationThatADoubleSumLoses) {
  ExactSum s;
  for (double v : {1e100, 1.0, -1e100, 1e-300, 3.0}) s.add(v);
  EXPECT_EQ(s.value(), 4.0);  // a left-to-right double sum gives 3
  ExactSum t;
  t.add(0.1);
  t.add(0.2);
  t.add(-0.3);
  // The exact sum of the three doubles (not 0, not the double sum 5.55e-17).
  EXPECT_EQ(t.value(), std::ldexp(1.0, -55));
}

TEST(ExactSum, TheSameBitsInAnyOrderAndAnySplit) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-60, 60);
  std::vector<double> terms(20000);
  for (double& v : terms) v = std::ldexp(mantissa(rng), exponent(rng));
  ExactSum forward;
  for (double v : terms) forward.add(v);
  std::shuffle(terms.begin(), terms.end(), rng);
  // Three "ranks" of unequal size, merged in another order.
  ExactSum a, b, c;
  for (std::size_t i = 0; i < terms.size(); ++i) (i < 5000 ? a : i < 6000 ? b : c).add(terms[i]);
  c.merge(a);
  c.merge(b);
  EXPECT_EQ(forward.value(), c.value());
  // Within an ulp of a long-double reference.
  long double reference = 0;
  for (double v : terms) reference += v;
  EXPECT_NEAR(forward.value(), static_cast<double>(reference), 4 * std::abs(forward.value()) * 1e-16);
}

TEST(ExactSum, ExtremesSubnormalsAndNonFinite) {
  ExactSum s;
  const double big = std::numeric_limits<double>::max(), tiny = std::numeric_limits<double>::denorm_min();
  s.add(big);
  s.add(tiny);
  s.add(-big);
  EXPECT_EQ(s.value(), tiny);
  ExactSum negative;
  negative.add(-2.5);
  negative.add(-1e-20);
  EXPECT_EQ(negative.value(), -2.5 - 1e-20);
  ExactSum nan;
  nan.add(1.0);
  nan.add(std::numeric_limits<double>::quiet_NaN());
  EXPECT_TRUE(std::isnan(nan.value()));
  ExactSum inf;
  inf.add(std::numeric_limits<double>::infinity());
  EXPECT_EQ(inf.value(), std::numeric_limits<double>::infinity());
  EXPECT_EQ(ExactSum{}.value(), 0.0);
}

}  // namespace
}  // namespace stagger
