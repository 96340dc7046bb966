// The donor remainder bound of the limited remap (lib/src/ale/remap.cpp, gather_fluxes;
// docs/ale.md, "Reconstruction and limiter"): a zone that gives most of its mass away through
// outflows whose values sit at the top of its bounds is left within them, conservatively, and
// a new value off its bounds by rounding only does not set it off.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "ale/remap.hpp"
#include "remap_state.hpp"
#include "stagger/mesh.hpp"
#include "stagger/meshgen.hpp"
#include "support/bitwise.hpp"

namespace {

using stagger::Index;
using stagger::Mesh;

struct Centre {
  double x, y;
};

// The mean of a zone's vertices: the centre of its median-mesh corners, as in the remap.
Centre vertex_mean(const Mesh& m, Index z) {
  const Index b = m.zone_corner_begin[z], n = m.zone_corner_begin[z + 1] - b;
  Centre c{0, 0};
  for (Index k = 0; k < n; ++k) c.x += m.x[m.corner_point[b + k]] / n, c.y += m.y[m.corner_point[b + k]] / n;
  return c;
}

// Area of corner k of zone z: (x_k, mid(k, k+1), centre, mid(k-1, k)).
double corner_area(const Mesh& m, Index z, Index k) {
  const Index b = m.zone_corner_begin[z], n = m.zone_corner_begin[z + 1] - b;
  const Index p = m.corner_point[b + k], pn = m.corner_point[b + (k + 1) % n], pp = m.corner_point[b + (k + n - 1) % n];
  const Centre g = vertex_mean(m, z);
  const double qx[4] = {m.x[p], 0.5 * (m.x[p] + m.x[pn]), g.x, 0.5 * (m.x[p] + m.x[pp])};
  const double qy[4] = {m.y[p], 0.5 * (m.y[p] + m.y[pn]), g.y, 0.5 * (m.y[p] + m.y[pp])};
  double a = 0;
  for (int i = 0; i < 4; ++i) a += qx[i] * qy[(i + 1) % 4] - qx[(i + 1) % 4] * qy[i];
  return 0.5 * a;
}

struct State : stagger::testing::RemapState {
  double sum_mass() const {
    double t = 0;
    for (double v : zone_mass) t += v;
    return t;
  }
  double sum_me() const {
    double t = 0;
    for (std::size_t z = 0; z < zone_mass.size(); ++z) t += zone_mass[z] * e[z];
    return t;
  }
};

// Corner masses from a density per zone (corner_rho(z, k)), the zone and point masses their sums.
template <class CornerRho, class E>
State make_state(const Mesh& m, CornerRho corner_rho, E energy) {
  State st;
  st.zero(m);
  const Index nz = m.num_zones(), np = m.num_points();
  for (Index z = 0; z < nz; ++z) {
    const Index b = m.zone_corner_begin[z], n = m.zone_corner_begin[z + 1] - b;
    for (Index k = 0; k < n; ++k) {
      const double mass = corner_rho(z, k) * corner_area(m, z, k);
      st.corner_mass[b + k] = mass;
      st.zone_mass[z] += mass;
      st.point_mass[m.corner_point[b + k]] += mass;
    }
    const Centre g = vertex_mean(m, z);
    st.e[z] = energy(g.x, g.y);
    st.s[z] = 1.0 + 0.25 * g.y;
  }
  for (Index p = 0; p < np; ++p) st.vx[p] = 0.5 * m.y[p], st.vy[p] = -0.25 * m.x[p];
  return st;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return stagger::testing::bitwise_equal(a, b);
}

// A row of five unit zones; zone 2 (x in [2, 3]) holds 90 % of its mass in its two corners at
// x = 3 (its subcell densities have drifted apart, as they do in a sheared flow), and its
// specific value 0.2 lies low in its bounds [0, 1] (neighbours 0 and 1), its limited gradient
// pointing up toward x = 3. The side x = 3 moves to x = 2.6: zone 2 gives 72 % of its mass to
// zone 3 through that side, with a mean value of 0.32, within its bounds, but the remainder
// keeps (0.2 - 0.72 * 0.32) / 0.28 = -0.11, below them.
struct Row {
  Mesh mesh = stagger::build_mesh(stagger::meshgen::rectangle(0, 5, 0, 1, 5, 1));
  Index zone[5];  // by column
  std::vector<double> xn, yn;
  explicit Row(double side = 2.6) {
    for (Index z = 0; z < 5; ++z) zone[static_cast<int>(std::floor(vertex_mean(mesh, z).x))] = z;
    xn = mesh.x, yn = mesh.y;
    for (Index p = 0; p < mesh.num_points(); ++p)
      if (mesh.x[p] == 3) xn[p] = side;
  }
  State state() const {
    const Index donor = zone[2];
    const Mesh& m = mesh;
    return make_state(
        m,
        [&](Index z, Index k) {
          if (z != donor) return vertex_mean(m, z).x > 3 ? 2.0 : 1.0;
          return m.x[m.corner_point[m.zone_corner_begin[z] + k]] == 3 ? 1.8 : 0.2;  // zone mass 1, density 1
        },
        [](double x, double) { return x < 2   ? 0.0
                                      : x < 3 ? 0.2
                                              : 1.0; });
  }
  State remapped(bool bound) const {
    State st = state();
    const std::vector<int> material(mesh.num_zones(), 0);
    stagger::Remapper remapper(mesh, material);
    remapper.set_remainder_bound(bound);
    stagger::RemapFields f = st.fields();
    remapper.remap(mesh.x.data(), mesh.y.data(), xn.data(), yn.data(), f, true);
    return st;
  }
};

TEST(RemainderBound, WithoutItAZoneGivingMostOfItsMassAwayLeavesItsBounds) {
  const Row row;
  const State before = row.state();
  EXPECT_NEAR(before.zone_mass[row.zone[2]], 1.0, 1e-15);
  const State st = row.remapped(false);
  const Index z = row.zone[2];
  // 0.28 of its mass is left, with a value far below the lowest of its neighbourhood (0).
  EXPECT_NEAR(st.zone_mass[z], 0.28, 1e-12);
  EXPECT_LT(st.e[z], -0.1);
  EXPECT_NEAR(st.e[z], (0.2 - 0.72 * 0.32) / 0.28, 1e-12);
}

TEST(RemainderBound, KeepsThatZoneWithinItsBoundsAndConserves) {
  const Row row;
  const State before = row.state(), off = row.remapped(false), on = row.remapped(true);
  const Index z = row.zone[2];
  // The largest share of the outflows' deviation that keeps it within [0, 1]: at 0, to rounding.
  EXPECT_GE(on.e[z], -1e-15);
  EXPECT_LE(on.e[z], 1e-15);
  // Only the values the outflows carry change: every mass bitwise, the other zones' values
  // bitwise, and the receiving zone gets what the donor kept.
  EXPECT_TRUE(same_bits(on.zone_mass, off.zone_mass));
  EXPECT_TRUE(same_bits(on.corner_mass, off.corner_mass));
  EXPECT_TRUE(same_bits(on.point_mass, off.point_mass));
  EXPECT_TRUE(same_bits(on.vx, off.vx));
  EXPECT_TRUE(same_bits(on.s, off.s));  // the second field stayed within its bounds
  for (int col : {0, 1, 4}) EXPECT_EQ(on.e[row.zone[col]], off.e[row.zone[col]]) << "column " << col;
  const Index receiver = row.zone[3];
  EXPECT_LT(on.e[receiver], off.e[receiver]);
  EXPECT_GE(on.e[receiver], 0.0);
  EXPECT_LE(on.e[receiver], 1.0);
  // Conservation of mass and of mass x value, to round-off.
  EXPECT_NEAR(on.sum_mass(), before.sum_mass(), 1e-15 * before.sum_mass());
  EXPECT_NEAR(on.sum_me(), before.sum_me(), 1e-15 * std::abs(before.sum_me()));
  EXPECT_NEAR(off.sum_me(), before.sum_me(), 1e-15 * std::abs(before.sum_me()));
}

// The same row with the side moved to x = 3 - d, d = 1/3 + 1e-15: with d = 1/3 exactly the
// remainder's value is exactly 0, the low end of zone 2's bounds (1 - 3.6 d + 1.8 d^2 = 0 for
// any value of zone 2: its limited gradient scales with it), so it lands below them by about
// 1e-15, rounding of the order of what the sums themselves make. The bound must not act on that:
// a bound that did would change the outflows' values (and cost the one-thread remap its
// direct sums, docs/ale.md "Remap cost"). Every array is bitwise the one without the bound.
TEST(RemainderBound, ARoundingLevelExcursionLeavesTheFluxesBitwise) {
  const Row row(3 - (1.0 / 3.0 + 1e-15));
  const State off = row.remapped(false), on = row.remapped(true);
  const Index z = row.zone[2];
  EXPECT_NEAR(off.zone_mass[z], 0.4, 1e-14);
  EXPECT_LT(off.e[z], 0.0);     // outside [0, 1] ...
  EXPECT_GT(off.e[z], -1e-14);  // ... by rounding
  for (const auto& [a, b] :
       {std::pair{&on.e, &off.e}, std::pair{&on.s, &off.s}, std::pair{&on.zone_mass, &off.zone_mass},
        std::pair{&on.corner_mass, &off.corner_mass}, std::pair{&on.vx, &off.vx}, std::pair{&on.kinetic, &off.kinetic}})
    EXPECT_TRUE(same_bits(*a, *b));
}

}  // namespace
