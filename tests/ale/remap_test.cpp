// The swept-face remap on its own (lib/src/ale/remap.hpp; docs/ale.md, "Remap"): identity,
// conservation, linear exactness, bounds and order of accuracy.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <vector>

#include "ale/remap.hpp"
#include "remap_state.hpp"
#include "stagger/mesh.hpp"
#include "stagger/meshgen.hpp"

namespace {

using stagger::Index;
using stagger::Mesh;

// A smooth displacement that vanishes on the boundary of the unit square.
double bump(double x, double y) {
  return std::sin(M_PI * x) * std::sin(M_PI * y);
}

// The unit square, n x n, with its interior points moved smoothly (a non-uniform mesh).
Mesh square_mesh(int n, double distortion = 0.1) {
  Mesh m = stagger::build_mesh(stagger::meshgen::rectangle(0, 1, 0, 1, n, n));
  for (Index p = 0; p < m.num_points(); ++p) {
    const double x = m.x[p], y = m.y[p];
    m.x[p] = x + distortion * bump(x, y) * std::sin(2 * M_PI * y) / 2;
    m.y[p] = y + distortion * bump(x, y) * std::sin(2 * M_PI * x) / 3;
  }
  return m;
}

double polygon_area(const Mesh& m, const std::vector<double>& x, const std::vector<double>& y, Index z) {
  double a = 0;
  const Index b = m.zone_corner_begin[z], n = m.zone_corner_begin[z + 1] - b;
  for (Index k = 0; k < n; ++k) {
    const Index p = m.corner_point[b + k], q = m.corner_point[b + (k + 1) % n];
    a += x[p] * y[q] - x[q] * y[p];
  }
  return 0.5 * a;
}

// Integral of (a + b x + c y) over zone z at (x, y), by triangles from the first vertex.
double linear_integral(const Mesh& m, const std::vector<double>& x, const std::vector<double>& y, Index z, double a,
                       double b, double c) {
  const Index first = m.zone_corner_begin[z], n = m.zone_corner_begin[z + 1] - first;
  const Index p0 = m.corner_point[first];
  double sum = 0;
  for (Index k = 1; k + 1 < n; ++k) {
    const Index p1 = m.corner_point[first + k], p2 = m.corner_point[first + k + 1];
    const double area = 0.5 * ((x[p1] - x[p0]) * (y[p2] - y[p0]) - (x[p2] - x[p0]) * (y[p1] - y[p0]));
    const double cx = (x[p0] + x[p1] + x[p2]) / 3, cy = (y[p0] + y[p1] + y[p2]) / 3;
    sum += area * (a + b * cx + c * cy);
  }
  return sum;
}

// A state on a mesh: zone density rho(x, y) (zone means), specific energy e, velocity v,
// median-mesh corner masses and the point masses they sum to.
using State = stagger::testing::RemapState;

// Every array of two states bitwise equal (the kinetic energies too, unless told otherwise).
void expect_same_bits(const State& a, const State& b, bool kinetic = true) {
  EXPECT_EQ(a.zone_mass, b.zone_mass);
  EXPECT_EQ(a.corner_mass, b.corner_mass);
  EXPECT_EQ(a.point_mass, b.point_mass);
  EXPECT_EQ(a.vx, b.vx);
  EXPECT_EQ(a.vy, b.vy);
  EXPECT_EQ(a.e, b.e);
  EXPECT_EQ(a.s, b.s);
  if (kinetic) {
    EXPECT_EQ(a.kinetic, b.kinetic);
  }
}

template <class Rho, class E, class V>
State make_state(const Mesh& m, Rho rho, E energy, V velocity) {
  State st;
  st.zero(m);
  const Index nz = m.num_zones(), np = m.num_points();
  for (Index z = 0; z < nz; ++z) {
    const Index b = m.zone_corner_begin[z], n = m.zone_corner_begin[z + 1] - b;
    double cx = 0, cy = 0;
    for (Index k = 0; k < n; ++k) cx += m.x[m.corner_point[b + k]] / n, cy += m.y[m.corner_point[b + k]] / n;
    const double r = rho(cx, cy);
    const double area = polygon_area(m, m.x, m.y, z);
    for (Index k = 0; k < n; ++k) {
      // Median-mesh corner areas: (x_k, mid(k, k+1), centre, mid(k-1, k)).
      const Index p = m.corner_point[b + k], pn = m.corner_point[b + (k + 1) % n],
                  pp = m.corner_point[b + (k + n - 1) % n];
      const double qx[4] = {m.x[p], 0.5 * (m.x[p] + m.x[pn]), cx, 0.5 * (m.x[p] + m.x[pp])};
      const double qy[4] = {m.y[p], 0.5 * (m.y[p] + m.y[pn]), cy, 0.5 * (m.y[p] + m.y[pp])};
      double a = 0;
      for (int i = 0; i < 4; ++i) a += qx[i] * qy[(i + 1) % 4] - qx[(i + 1) % 4] * qy[i];
      st.corner_mass[b + k] = 0.5 * a * r;
      st.point_mass[p] += 0.5 * a * r;
    }
    st.zone_mass[z] = r * area;
    st.e[z] = energy(cx, cy);
    st.s[z] = 1.0 - cx * cx;
  }
  for (Index p = 0; p < np; ++p) {
    const auto v = velocity(m.x[p], m.y[p]);
    st.vx[p] = v[0], st.vy[p] = v[1];
  }
  return st;
}

// New positions: the interior moved by a smooth field of amplitude `amp` (boundary fixed).
void moved(const Mesh& m, double amp, double phase, std::vector<double>& xn, std::vector<double>& yn) {
  xn = m.x, yn = m.y;
  for (Index p = 0; p < m.num_points(); ++p) {
    const double x = m.x[p], y = m.y[p];
    xn[p] = x + amp * bump(x, y) * std::cos(3 * y + phase);
    yn[p] = y + amp * bump(x, y) * std::sin(2 * x - phase);
  }
}

double sum(const std::vector<double>& v) {
  return std::accumulate(v.begin(), v.end(), 0.0);
}

TEST(Remap, NoMotionIsTheIdentityBitwise) {
  const Mesh m = square_mesh(12);
  const std::vector<int> material(m.num_zones(), 0);
  stagger::Remapper remapper(m, material);
  State st = make_state(
      m, [](double x, double y) { return 1 + 0.5 * std::sin(5 * x) * y; }, [](double x, double) { return 2 + x; },
      [](double x, double y) {
        return std::array<double, 2>{std::sin(3 * y), x * x};
      });
  const State before = st;
  auto f = st.fields();
  remapper.remap(m.x.data(), m.y.data(), m.x.data(), m.y.data(), f, true);
  expect_same_bits(st, before, false);
  for (Index p = 0; p < m.num_points(); ++p)
    EXPECT_EQ(st.kinetic[p], 0.5 * st.point_mass[p] * (st.vx[p] * st.vx[p] + st.vy[p] * st.vy[p]));
}

TEST(Remap, RandomSmoothMotionConservesToRoundOff) {
  const Mesh m = square_mesh(16);
  const std::vector<int> material(m.num_zones(), 0);
  stagger::Remapper remapper(m, material);
  State st = make_state(
      m, [](double x, double y) { return 1 + 0.5 * std::sin(5 * x) * y + (x > 0.6 ? 2 : 0); },
      [](double x, double y) { return 2 + x * y; },
      [](double x, double y) {
        return std::array<double, 2>{std::sin(3 * y), x * x - 0.3};
      });
  const double mass0 = sum(st.zone_mass);
  double energy0 = 0, px0 = 0, py0 = 0, ke0 = 0;
  for (Index z = 0; z < m.num_zones(); ++z) energy0 += st.zone_mass[z] * st.e[z];
  for (Index p = 0; p < m.num_points(); ++p) {
    px0 += st.point_mass[p] * st.vx[p], py0 += st.point_mass[p] * st.vy[p];
    ke0 += 0.5 * st.point_mass[p] * (st.vx[p] * st.vx[p] + st.vy[p] * st.vy[p]);
  }
  std::vector<double> xo = m.x, yo = m.y, xn, yn;
  for (int step = 0; step < 20; ++step) {
    moved(m, 0.01, 0.3 * step, xn, yn);
    auto f = st.fields();
    remapper.remap(xo.data(), yo.data(), xn.data(), yn.data(), f, true);
    xo = xn, yo = yn;
  }
  double energy = 0, px = 0, py = 0, ke = 0;
  for (Index z = 0; z < m.num_zones(); ++z) energy += st.zone_mass[z] * st.e[z];
  for (Index p = 0; p < m.num_points(); ++p) {
    px += st.point_mass[p] * st.vx[p], py += st.point_mass[p] * st.vy[p];
    ke += st.kinetic[p];  // the carried kinetic energy of the last remap
  }
  EXPECT_NEAR(sum(st.zone_mass), mass0, 1e-14 * mass0);
  EXPECT_NEAR(sum(st.corner_mass), mass0, 1e-14 * mass0);
  EXPECT_NEAR(sum(st.point_mass), mass0, 1e-14 * mass0);
  EXPECT_NEAR(energy, energy0, 1e-14 * energy0);
  EXPECT_NEAR(px, px0, 1e-14 * mass0);
  EXPECT_NEAR(py, py0, 1e-14 * mass0);
  // The momentum remap loses kinetic energy (what the fix-up gives back) and creates none;
  // 20 second-order remaps of this smooth field lose little of it.
  double ke_now = 0;
  for (Index p = 0; p < m.num_points(); ++p)
    ke_now += 0.5 * st.point_mass[p] * (st.vx[p] * st.vx[p] + st.vy[p] * st.vy[p]);
  EXPECT_LE(ke_now, ke);                // the last remap created no kinetic energy
  EXPECT_GT(ke_now, (1 - 1e-3) * ke0);  // 20 remaps lose 1.0e-4 of it (second order)
  // Over one remap, the carried kinetic energy equals the kinetic energy before it.
  double ke_last = 0;
  {
    State copy = st;
    for (Index p = 0; p < m.num_points(); ++p)
      ke_last += 0.5 * copy.point_mass[p] * (copy.vx[p] * copy.vx[p] + copy.vy[p] * copy.vy[p]);
    moved(m, 0.01, 7.0, xn, yn);
    auto f = copy.fields();
    remapper.remap(xo.data(), yo.data(), xn.data(), yn.data(), f, true);
    EXPECT_NEAR(sum(copy.kinetic), ke_last, 1e-14 * ke_last);
    double ke_new = 0;
    for (Index p = 0; p < m.num_points(); ++p)
      ke_new += 0.5 * copy.point_mass[p] * (copy.vx[p] * copy.vx[p] + copy.vy[p] * copy.vy[p]);
    // The remap of momentum loses kinetic energy (what the fix-up gives back), a little.
    EXPECT_LE(ke_new, sum(copy.kinetic));
    EXPECT_GT(ke_new, 0.99 * sum(copy.kinetic));
  }
  // Every corner mass stayed a positive part of its zone and point.
  for (Index z = 0; z < m.num_zones(); ++z) {
    double s = 0;
    for (Index c = m.zone_corner_begin[z]; c < m.zone_corner_begin[z + 1]; ++c) s += st.corner_mass[c];
    EXPECT_NEAR(s, st.zone_mass[z], 1e-13 * st.zone_mass[z]);
  }
  for (Index p = 0; p < m.num_points(); ++p) {
    double s = 0;
    for (Index k = m.point_corner_begin[p]; k < m.point_corner_begin[p + 1]; ++k)
      s += st.corner_mass[m.point_corners[k]];
    EXPECT_NEAR(s, st.point_mass[p], 1e-13 * st.point_mass[p]);
  }
}

TEST(Remap, LinearFieldsAreReproducedExactly) {
  const Mesh m = square_mesh(14);
  const std::vector<int> material(m.num_zones(), 0);
  stagger::Remapper remapper(m, material);
  for (bool limiter : {true, false}) {
    // Linear density with constant specific fields, and constant density with linear e.
    State a = make_state(
        m, [](double x, double y) { return 2 + x - 0.5 * y; }, [](double, double) { return 3.0; },
        [](double, double) {
          return std::array<double, 2>{1.0, -2.0};
        });
    State b = make_state(
        m, [](double, double) { return 1.5; }, [](double x, double y) { return 1 + 2 * x + 3 * y; },
        [](double, double) {
          return std::array<double, 2>{0.0, 0.0};
        });
    // The zone means of the linear fields on the initial mesh (make_state samples at the
    // vertex average, which is not the centroid).
    for (Index z = 0; z < m.num_zones(); ++z) {
      a.zone_mass[z] = linear_integral(m, m.x, m.y, z, 2, 1, -0.5);
      // Corner masses: the density's integral over each median-mesh corner.
      const Index cb = m.zone_corner_begin[z], n = m.zone_corner_begin[z + 1] - cb;
      double gx = 0, gy = 0;
      for (Index k = 0; k < n; ++k) gx += m.x[m.corner_point[cb + k]] / n, gy += m.y[m.corner_point[cb + k]] / n;
      for (Index k = 0; k < n; ++k) {
        const Index p = m.corner_point[cb + k], pn = m.corner_point[cb + (k + 1) % n],
                    pp = m.corner_point[cb + (k + n - 1) % n];
        const double qx[4] = {m.x[p], 0.5 * (m.x[p] + m.x[pn]), gx, 0.5 * (m.x[p] + m.x[pp])};
        const double qy[4] = {m.y[p], 0.5 * (m.y[p] + m.y[pn]), gy, 0.5 * (m.y[p] + m.y[pp])};
        double ia = 0, ib = 0;  // integrals of 2 + x - y/2 (a) and 1.5 (b) by two triangles
        for (int t = 1; t < 3; ++t) {
          const double ar = 0.5 * ((qx[t] - qx[0]) * (qy[t + 1] - qy[0]) - (qx[t + 1] - qx[0]) * (qy[t] - qy[0]));
          ia += ar * (2 + (qx[0] + qx[t] + qx[t + 1]) / 3 - 0.5 * (qy[0] + qy[t] + qy[t + 1]) / 3);
          ib += ar * 1.5;
        }
        a.corner_mass[cb + k] = ia;
        b.corner_mass[cb + k] = ib;
      }
      b.e[z] = linear_integral(m, m.x, m.y, z, 1, 2, 3) / polygon_area(m, m.x, m.y, z);
      b.zone_mass[z] = 1.5 * polygon_area(m, m.x, m.y, z);
    }
    std::vector<double> xn, yn;
    moved(m, 0.012, 0.5, xn, yn);
    auto fa = a.fields();
    auto fb = b.fields();
    remapper.remap(m.x.data(), m.y.data(), xn.data(), yn.data(), fa, limiter);
    remapper.remap(m.x.data(), m.y.data(), xn.data(), yn.data(), fb, limiter);
    double worst_mass = 0, worst_e = 0, worst_v = 0;
    for (Index z = 0; z < m.num_zones(); ++z) {
      worst_mass = std::max(worst_mass, std::abs(a.zone_mass[z] - linear_integral(m, xn, yn, z, 2, 1, -0.5)));
      const double exact_e = linear_integral(m, xn, yn, z, 1, 2, 3) / polygon_area(m, xn, yn, z);
      worst_e = std::max(worst_e, std::abs(b.e[z] - exact_e));
      worst_e = std::max(worst_e, std::abs(a.e[z] - 3.0));
    }
    for (Index p = 0; p < m.num_points(); ++p)
      worst_v = std::max({worst_v, std::abs(a.vx[p] - 1.0), std::abs(a.vy[p] + 2.0)});
    EXPECT_LT(worst_mass, 1e-15) << "limiter " << limiter;
    EXPECT_LT(worst_e, 1e-12) << "limiter " << limiter;
    EXPECT_LT(worst_v, 1e-12) << "limiter " << limiter;
  }
}

TEST(Remap, TheLimiterMakesNoNewDensityExtrema) {
  const Mesh m = square_mesh(20);
  const std::vector<int> material(m.num_zones(), 0);
  stagger::Remapper remapper(m, material);
  // A density with jumps and a peak.
  State st = make_state(
      m,
      [](double x, double y) {
        return (x > 0.45 ? 4.0 : 1.0) + (std::hypot(x - 0.3, y - 0.6) < 0.15 ? 3.0 : 0.0) + 0.2 * std::sin(9 * y);
      },
      [](double x, double) { return x > 0.5 ? 1.0 : 2.0; },
      [](double, double) {
        return std::array<double, 2>{0.0, 0.0};
      });
  std::vector<double> xo = m.x, yo = m.y, xn, yn;
  double lo = 1e300, hi = -1e300;
  for (Index z = 0; z < m.num_zones(); ++z) {
    const double r = st.zone_mass[z] / polygon_area(m, xo, yo, z);
    lo = std::min(lo, r), hi = std::max(hi, r);
  }
  for (int step = 0; step < 15; ++step) {
    moved(m, 0.015, 0.7 * step, xn, yn);
    auto f = st.fields();
    remapper.remap(xo.data(), yo.data(), xn.data(), yn.data(), f, true);
    xo = xn, yo = yn;
    for (Index z = 0; z < m.num_zones(); ++z) {
      const double r = st.zone_mass[z] / polygon_area(m, xo, yo, z);
      ASSERT_GE(r, lo * (1 - 1e-12)) << "zone " << z << " step " << step;
      ASSERT_LE(r, hi * (1 + 1e-12)) << "zone " << z << " step " << step;
      ASSERT_GE(st.e[z], 1.0 - 1e-12);
      ASSERT_LE(st.e[z], 2.0 + 1e-12);
    }
  }
}

// The interior of the unit square n x n slides by up to (0.2, dy) and comes back, in 10 n / 4
// remaps of about a quarter zone each, ending on the initial mesh exactly.
void slide_there_and_back(const Mesh& m, int n, double dy, State& st, stagger::Remapper& remapper, bool limiter) {
  const int steps = 10 * n / 8;
  std::vector<double> xo = m.x, yo = m.y, xn(m.x.size()), yn(m.y.size());
  for (int j = 1; j <= 2 * steps; ++j) {
    const double t = static_cast<double>(j) / (2 * steps);
    for (Index p = 0; p < m.num_points(); ++p) {
      const double x = m.x[p], y = m.y[p];
      const double w = std::pow(std::sin(M_PI * x) * std::sin(M_PI * y), 2);
      xn[p] = x + 0.2 * w * std::sin(M_PI * t);
      yn[p] = y + dy * w * std::sin(M_PI * t);
    }
    if (j == 2 * steps) xn = m.x, yn = m.y;
    auto f = st.fields();
    remapper.remap(xo.data(), yo.data(), xn.data(), yn.data(), f, limiter);
    xo = xn, yo = yn;
  }
}

// L1 error of the density after moving the mesh there and back in `steps` remaps.
double cyclic_remap_error(int n, bool limiter) {
  Mesh m = stagger::build_mesh(stagger::meshgen::rectangle(0, 1, 0, 1, n, n));
  const std::vector<int> material(m.num_zones(), 0);
  stagger::Remapper remapper(m, material);
  auto rho = [](double x, double y) { return 1 + 0.5 * std::sin(2 * M_PI * x) * std::sin(2 * M_PI * y); };
  State st = make_state(
      m, rho, [](double, double) { return 1.0; },
      [](double, double) {
        return std::array<double, 2>{0.0, 0.0};
      });
  // Exact zone masses (the profile's integral, by a 4x4 Gauss rule on each square zone).
  const double g[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
  for (Index z = 0; z < m.num_zones(); ++z) {
    const Index b = m.zone_corner_begin[z];
    const double x0 = m.x[m.corner_point[b]], y0 = m.y[m.corner_point[b]], h = 1.0 / n;
    double s = 0;
    for (double gx : g)
      for (double gy : g) s += 0.25 * rho(x0 + gx * h, y0 + gy * h);
    st.zone_mass[z] = s * h * h;
  }
  const std::vector<double> exact = st.zone_mass;
  // The interior slides right by up to 0.2 and comes back, about a quarter zone per remap.
  slide_there_and_back(m, n, 0.0, st, remapper, limiter);
  double error = 0;
  for (Index z = 0; z < m.num_zones(); ++z) error += std::abs(st.zone_mass[z] - exact[z]);
  return error;
}

TEST(Remap, RepeatedRemapConvergesAtSecondOrder) {
  for (bool limiter : {false, true}) {
    const double e1 = cyclic_remap_error(16, limiter), e2 = cyclic_remap_error(32, limiter),
                 e3 = cyclic_remap_error(64, limiter);
    const double order1 = std::log2(e1 / e2), order2 = std::log2(e2 / e3);
    RecordProperty(limiter ? "order_limited" : "order_unlimited", std::to_string(order2));
    std::printf("cyclic remap, limiter %d: L1 errors %.3e %.3e %.3e, orders %.2f %.2f\n", limiter, e1, e2, e3, order1,
                order2);
    EXPECT_GE(order2, 1.8) << "limiter " << limiter << ": errors " << e1 << " " << e2 << " " << e3 << ", orders "
                           << order1 << " " << order2;
  }
}

TEST(Remap, ResultDoesNotDependOnTheThreadCount) {
  // Large enough for every loop of the remap to run in parallel (more than 4096 zones and
  // points); a density jump and the limiter, so the clamps and the corner limiter act. One
  // thread adds each flux straight into its cells' sums, two go through the slots and the
  // gathers: the same bits.
  const Mesh m = square_mesh(72);
  ASSERT_GT(m.num_zones(), 4096);
  ASSERT_GT(m.num_points(), 4096);
  const std::vector<int> material(m.num_zones(), 0);
  const State start = make_state(
      m, [](double x, double y) { return 1 + 0.5 * std::sin(5 * x) * y + (x > 0.6 ? 2 : 0); },
      [](double x, double y) { return 2 + x * y + (y > 0.4 ? 1 : 0); },
      [](double x, double y) {
        return std::array<double, 2>{std::sin(3 * y), x * x - 0.3};
      });
  const auto run = [&](int threads) {
    const int before = omp_get_max_threads();
    omp_set_num_threads(threads);
    stagger::Remapper remapper(m, material);
    State st = start;
    std::vector<double> xo = m.x, yo = m.y, xn, yn;
    for (int step = 0; step < 3; ++step) {
      moved(m, 0.004, 0.7 * step, xn, yn);
      auto f = st.fields();
      remapper.remap(xo.data(), yo.data(), xn.data(), yn.data(), f, true);
      xo = xn, yo = yn;
    }
    omp_set_num_threads(before);
    return st;
  };
  const State one = run(1), two = run(2);
  expect_same_bits(one, two);
  EXPECT_NE(one.zone_mass, start.zone_mass);  // the remap did something
}

TEST(Remap, PartialMotionAndTheRemainderBoundGiveTheSameBitsOnAnyThreadCount) {
  // Only the left part of the mesh moves (the zones at rest get no gradient, bounds or fluxes,
  // docs/ale.md "Remap cost"), by a large step over energy jumps of six decades, so that the
  // donor remainder bound acts (44 times): on one thread it changes the direct sums, on two
  // the slots.
  const Mesh m = square_mesh(72);
  const std::vector<int> material(m.num_zones(), 0);
  const State start = make_state(
      m, [](double x, double y) { return 1 + 0.5 * std::sin(5 * x) * y + (x > 0.3 ? 2 : 0); },
      [](double x, double y) { return std::sin(40 * x) * std::sin(40 * y) > 0.2 ? 1e6 : 1.0 + x; },
      [](double x, double y) {
        return std::array<double, 2>{std::sin(3 * y), x * x - 0.3};
      });
  const auto run = [&](int threads, long& bounded) {
    const int before = omp_get_max_threads();
    omp_set_num_threads(threads);
    stagger::Remapper remapper(m, material);
    State st = start;
    std::vector<double> xo = m.x, yo = m.y, xn, yn;
    for (int step = 0; step < 3; ++step) {
      moved(m, 0.012, 0.7 * step, xn, yn);  // up to 0.86 of an edge
      for (Index p = 0; p < m.num_points(); ++p)
        if (m.x[p] > 0.5) xn[p] = xo[p], yn[p] = yo[p];
      auto f = st.fields();
      remapper.remap(xo.data(), yo.data(), xn.data(), yn.data(), f, true);
      xo = xn, yo = yn;
    }
    omp_set_num_threads(before);
    bounded = remapper.bounded_zones();
    return st;
  };
  long bounded_one = 0, bounded_two = 0;
  const State one = run(1, bounded_one), two = run(2, bounded_two);
  EXPECT_GT(bounded_one, 0);
  EXPECT_EQ(bounded_one, bounded_two);
  expect_same_bits(one, two);
  // The zones right of x = 0.6 (no point of theirs moved) keep their bits.
  Index still = 0;
  for (Index z = 0; z < m.num_zones(); ++z) {
    bool right = true;
    for (Index c = m.zone_corner_begin[z]; c < m.zone_corner_begin[z + 1]; ++c)
      right = right && m.x[m.corner_point[c]] > 0.6;
    if (!right) continue;
    ++still;
    EXPECT_EQ(one.zone_mass[z], start.zone_mass[z]);
    EXPECT_EQ(one.e[z], start.e[z]);
  }
  EXPECT_GT(still, 1000);
  std::printf("remainder bound acted in %ld zone remaps; %ld zones at rest\n", bounded_one, static_cast<long>(still));
}

// rz (docs/ale.md, "ALE in rz"): integral of (a + b x + c y) x dA (x = r) over the polygon
// q, by triangles from its first vertex with the edge-midpoint rule (exact for quadratics).
double rz_integral(const double* qx, const double* qy, int n, double a, double b, double c) {
  double sum = 0;
  const auto g = [&](double x, double y) { return (a + b * x + c * y) * x; };
  for (int t = 1; t + 1 < n; ++t) {
    const double x0 = qx[0], y0 = qy[0], x1 = qx[t], y1 = qy[t], x2 = qx[t + 1], y2 = qy[t + 1];
    const double area = 0.5 * ((x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0));
    sum += area / 3 *
           (g(0.5 * (x0 + x1), 0.5 * (y0 + y1)) + g(0.5 * (x1 + x2), 0.5 * (y1 + y2)) +
            g(0.5 * (x2 + x0), 0.5 * (y2 + y0)));
  }
  return sum;
}

double rz_zone_integral(const Mesh& m, const std::vector<double>& x, const std::vector<double>& y, Index z, double a,
                        double b, double c) {
  const Index first = m.zone_corner_begin[z], n = m.zone_corner_begin[z + 1] - first;
  double qx[8], qy[8];
  for (Index k = 0; k < n; ++k) qx[k] = x[m.corner_point[first + k]], qy[k] = y[m.corner_point[first + k]];
  return rz_integral(qx, qy, static_cast<int>(n), a, b, c);
}

// An rz state: density a + b x + c y, zone and median-mesh corner masses per radian, the
// point masses the sums of their corners' (zero on the axis x = 0, which is massless),
// specific energy e(x, y) (zone values: the means int rho e r dA / M of a linear e with a
// constant density, else sampled), velocity v(x, y).
template <class E, class V>
State make_rz_state(const Mesh& m, double a, double b, double c, E energy, V velocity) {
  State st;
  st.zero(m);
  const Index nz = m.num_zones(), np = m.num_points();
  st.vx.assign(np, 0);
  st.vy.assign(np, 0);
  for (Index z = 0; z < nz; ++z) {
    const Index cb = m.zone_corner_begin[z], n = m.zone_corner_begin[z + 1] - cb;
    double gx = 0, gy = 0;
    for (Index k = 0; k < n; ++k) gx += m.x[m.corner_point[cb + k]] / n, gy += m.y[m.corner_point[cb + k]] / n;
    for (Index k = 0; k < n; ++k) {
      const Index p = m.corner_point[cb + k], pn = m.corner_point[cb + (k + 1) % n],
                  pp = m.corner_point[cb + (k + n - 1) % n];
      const double qx[4] = {m.x[p], 0.5 * (m.x[p] + m.x[pn]), gx, 0.5 * (m.x[p] + m.x[pp])};
      const double qy[4] = {m.y[p], 0.5 * (m.y[p] + m.y[pn]), gy, 0.5 * (m.y[p] + m.y[pp])};
      st.corner_mass[cb + k] = rz_integral(qx, qy, 4, a, b, c);
      if (m.x[p] != 0) st.point_mass[p] += st.corner_mass[cb + k];
    }
    st.zone_mass[z] = rz_zone_integral(m, m.x, m.y, z, a, b, c);
    st.e[z] = energy(m, m.x, m.y, z);
    st.s[z] = 1.0 - gx * gx;
  }
  for (Index p = 0; p < np; ++p) {
    const auto v = velocity(m.x[p], m.y[p]);
    st.vx[p] = v[0], st.vy[p] = v[1];
  }
  return st;
}

// The interior moved as moved(), and the axis points slid along it (the ends fixed).
void moved_rz(const Mesh& m, double amp, double phase, std::vector<double>& xn, std::vector<double>& yn) {
  moved(m, amp, phase, xn, yn);
  for (Index p = 0; p < m.num_points(); ++p)
    if (m.x[p] == 0) yn[p] = m.y[p] + amp * std::sin(M_PI * m.y[p]) * std::cos(phase);
}

TEST(RemapRz, NoMotionIsTheIdentityBitwise) {
  const Mesh m = square_mesh(10);
  const std::vector<int> material(m.num_zones(), 0);
  stagger::Remapper remapper(m, material, true);
  State st = make_rz_state(
      m, 1.0, 0.3, -0.2, [](const Mesh&, auto&, auto&, Index z) { return 2.0 + 0.01 * z; },
      [](double x, double y) {
        return std::array<double, 2>{x * std::sin(3 * y), x * x + y};
      });
  const State before = st;
  auto f = st.fields();
  remapper.remap(m.x.data(), m.y.data(), m.x.data(), m.y.data(), f, true);
  expect_same_bits(st, before, false);
}

TEST(RemapRz, RandomSmoothMotionConservesMassMomentumAndEnergyPerRadian) {
  const Mesh m = square_mesh(16);
  const std::vector<int> material(m.num_zones(), 0);
  stagger::Remapper remapper(m, material, true);
  State st = make_rz_state(
      m, 1.0, 0.8, -0.3,
      [](const Mesh& mm, auto& x, auto& y, Index z) {
        return 2 + x[mm.corner_point[mm.zone_corner_begin[z]]] * y[mm.corner_point[mm.zone_corner_begin[z]]];
      },
      [](double x, double y) {
        return std::array<double, 2>{x * std::sin(3 * y), x * x - 0.3 + std::cos(2 * y)};
      });
  const auto totals = [&](const State& s, bool carried) {
    std::array<double, 4> t{};  // mass, z momentum, internal + kinetic energy, kinetic
    for (Index z = 0; z < m.num_zones(); ++z) t[0] += s.zone_mass[z], t[2] += s.zone_mass[z] * s.e[z];
    for (Index p = 0; p < m.num_points(); ++p) {
      t[1] += s.point_mass[p] * s.vy[p];
      t[3] += carried ? s.kinetic[p] : 0.5 * s.point_mass[p] * (s.vx[p] * s.vx[p] + s.vy[p] * s.vy[p]);
    }
    t[2] += t[3];
    return t;
  };
  const auto before = totals(st, false);
  std::vector<double> xo = m.x, yo = m.y, xn, yn;
  for (int step = 0; step < 12; ++step) {
    const auto start = totals(st, false);
    moved_rz(m, 0.01, 0.3 * step, xn, yn);
    auto f = st.fields();
    remapper.remap(xo.data(), yo.data(), xn.data(), yn.data(), f, true);
    xo = xn, yo = yn;
    // Per remap: the kinetic energy carried is the kinetic energy before it (the fix-up of
    // the simulation then gives the difference to the internal energy).
    const auto after = totals(st, true);
    EXPECT_NEAR(after[2], start[2], 1e-14 * start[2]) << "remap " << step;
    EXPECT_NEAR(after[1], start[1], 1e-14 * start[0]) << "remap " << step;
  }
  const auto end = totals(st, false);
  EXPECT_NEAR(end[0], before[0], 1e-14 * before[0]);
  EXPECT_NEAR(sum(st.corner_mass), before[0], 1e-14 * before[0]);
  for (Index p = 0; p < m.num_points(); ++p) {
    if (m.x[p] == 0) {
      EXPECT_EQ(st.point_mass[p], 0.0);  // the axis stays massless
      EXPECT_EQ(xo[p], 0.0);
      continue;
    }
    double s = 0;
    for (Index k = m.point_corner_begin[p]; k < m.point_corner_begin[p + 1]; ++k)
      s += st.corner_mass[m.point_corners[k]];
    EXPECT_NEAR(s, st.point_mass[p], 1e-13 * st.point_mass[p]) << "point " << p;
  }
  for (Index z = 0; z < m.num_zones(); ++z) {
    double s = 0;
    for (Index c = m.zone_corner_begin[z]; c < m.zone_corner_begin[z + 1]; ++c) s += st.corner_mass[c];
    EXPECT_NEAR(s, st.zone_mass[z], 1e-13 * st.zone_mass[z]);
  }
  EXPECT_NE(st.zone_mass, make_rz_state(
                              m, 1.0, 0.8, -0.3, [](const Mesh&, auto&, auto&, Index) { return 0.0; },
                              [](double, double) {
                                return std::array<double, 2>{0.0, 0.0};
                              })
                              .zone_mass);  // the remap did something
}

TEST(RemapRz, LinearFieldsAreReproducedExactly) {
  const Mesh m = square_mesh(14);
  const std::vector<int> material(m.num_zones(), 0);
  stagger::Remapper remapper(m, material, true);
  for (bool limiter : {true, false}) {
    // Linear density (per unit volume) with uniform velocity, and constant density with a
    // linear specific energy (zone values: its mass-weighted means).
    State a = make_rz_state(
        m, 2.0, 1.0, -0.5, [](const Mesh&, auto&, auto&, Index) { return 3.0; },
        [](double, double) {
          return std::array<double, 2>{0.0, -2.0};
        });
    const auto linear_e = [](const Mesh& mm, auto& x, auto& y, Index z) {
      return rz_zone_integral(mm, x, y, z, 1, 2, 3) / rz_zone_integral(mm, x, y, z, 1, 0, 0);
    };
    State b = make_rz_state(m, 1.5, 0, 0, linear_e, [](double, double) { return std::array<double, 2>{0.0, 0.0}; });
    std::vector<double> xn, yn;
    moved_rz(m, 0.012, 0.5, xn, yn);
    auto fa = a.fields();
    auto fb = b.fields();
    remapper.remap(m.x.data(), m.y.data(), xn.data(), yn.data(), fa, limiter);
    remapper.remap(m.x.data(), m.y.data(), xn.data(), yn.data(), fb, limiter);
    double worst_mass = 0, worst_e = 0, worst_v = 0;
    for (Index z = 0; z < m.num_zones(); ++z) {
      worst_mass = std::max(worst_mass, std::abs(a.zone_mass[z] - rz_zone_integral(m, xn, yn, z, 2, 1, -0.5)));
      worst_e = std::max(worst_e, std::abs(b.e[z] - linear_e(m, xn, yn, z)));
      worst_e = std::max(worst_e, std::abs(a.e[z] - 3.0));
    }
    for (Index p = 0; p < m.num_points(); ++p)
      worst_v = std::max({worst_v, std::abs(a.vx[p]), std::abs(a.vy[p] + 2.0)});
    EXPECT_LT(worst_mass, 1e-15) << "limiter " << limiter;
    EXPECT_LT(worst_e, 1e-12) << "limiter " << limiter;
    EXPECT_LT(worst_v, 1e-12) << "limiter " << limiter;
  }
}

// The momentum remap (docs/ale.md, "Momentum"): the point velocities of a smooth field after
// the mesh slid there and back in remaps of about a quarter zone each, against the initial
// ones; the point-mass-weighted L1 error over the (massive) points. Uniform density, so that
// only the velocity reconstruction (its gradients and limiter) decides the error.
double cyclic_velocity_error(int n, bool limiter, bool rz) {
  Mesh m = stagger::build_mesh(stagger::meshgen::rectangle(0, 1, 0, 1, n, n));
  const std::vector<int> material(m.num_zones(), 0);
  stagger::Remapper remapper(m, material, rz);
  // vx vanishes on the axis x = 0 (rz), as an axis point's radial velocity must.
  const auto velocity = [](double x, double y) {
    return std::array<double, 2>{0.5 * std::sin(2 * M_PI * x) * std::sin(2 * M_PI * y),
                                 1 + 0.5 * std::cos(2 * M_PI * x) * std::sin(2 * M_PI * y)};
  };
  State st = rz ? make_rz_state(
                      m, 1.0, 0, 0, [](const Mesh&, auto&, auto&, Index) { return 1.0; }, velocity)
                : make_state(
                      m, [](double, double) { return 1.0; }, [](double, double) { return 1.0; }, velocity);
  const std::vector<double> vx0 = st.vx, vy0 = st.vy;
  slide_there_and_back(m, n, 0.1, st, remapper, limiter);
  double error = 0, mass = 0;
  for (Index p = 0; p < m.num_points(); ++p) {
    error += st.point_mass[p] * (std::abs(st.vx[p] - vx0[p]) + std::abs(st.vy[p] - vy0[p]));
    mass += st.point_mass[p];
  }
  return error / mass;
}

void expect_second_order_velocity_remap(bool rz) {
  for (bool limiter : {false, true}) {
    const double e1 = cyclic_velocity_error(16, limiter, rz), e2 = cyclic_velocity_error(32, limiter, rz),
                 e3 = cyclic_velocity_error(64, limiter, rz);
    const double order1 = std::log2(e1 / e2), order2 = std::log2(e2 / e3);
    std::printf("cyclic velocity remap, rz %d limiter %d: L1 errors %.3e %.3e %.3e, orders %.2f %.2f\n", rz, limiter,
                e1, e2, e3, order1, order2);
    EXPECT_GE(order2, 1.8) << "rz " << rz << " limiter " << limiter << ": errors " << e1 << " " << e2 << " " << e3;
  }
}

// The kinetic energy the remap carries into each dual cell (for the fix-up), by an exact
// property: dK_p = K'_p - M'_p |v'_p|^2 / 2 is Galilean invariant. A flux carries
// 1/2 |u|^2 m + rho_c u . int (v - u), the corner term of the velocity reconstruction; with a
// uniform velocity U added everywhere it carries U . (its momentum) + 1/2 |U|^2 m more, which
// is what the new momentum's kinetic energy gains too, so every dK_p is the same. Without the
// corner term a flux misses rho_c U . int (v - u), and the fix-up would depend on the frame.
// The largest |dK_p(U) - dK_p(0)| against the largest |dK_p(0)|, one unlimited remap of a
// smooth field. (With the limiter the remapped velocities themselves move with the frame, by
// up to 2.5e-3 for U = (3, -2) here: the limiter's branches are not invariant; see the note
// in docs/ale.md, "Reconstruction and limiter".)
struct FrameDependence {
  double dk, velocity;  // largest change of dK_p (relative), of the velocity (absolute)
};
FrameDependence frame_dependence(bool rz, bool limiter) {
  const Mesh m = square_mesh(24);
  const std::vector<int> material(m.num_zones(), 0);
  std::vector<double> dk[2], vx[2], vy[2];
  for (int frame = 0; frame < 2; ++frame) {
    stagger::Remapper remapper(m, material, rz);
    // rz: no radial shift (the axis's radial velocity is 0); the axial one is a uniform motion.
    const double ux = frame == 0 || rz ? 0.0 : 3.0, uy = frame == 0 ? 0.0 : -2.0;
    const auto velocity = [&](double x, double y) {
      return std::array<double, 2>{ux + x * std::sin(2 * M_PI * x) * std::sin(2 * M_PI * y),
                                   uy + 0.5 * std::cos(2 * M_PI * x) * y};
    };
    State st =
        rz ? make_rz_state(
                 m, 1.0, 0.2, 0.0, [](const Mesh&, auto&, auto&, Index) { return 1.0; }, velocity)
           : make_state(
                 m, [](double x, double) { return 1.0 + 0.2 * x; }, [](double, double) { return 1.0; }, velocity);
    std::vector<double> xn, yn;
    if (rz)
      moved_rz(m, 0.012, 0.4, xn, yn);
    else
      moved(m, 0.012, 0.4, xn, yn);
    auto f = st.fields();
    remapper.remap(m.x.data(), m.y.data(), xn.data(), yn.data(), f, limiter);
    for (Index p = 0; p < m.num_points(); ++p)
      dk[frame].push_back(st.kinetic[p] - 0.5 * st.point_mass[p] * (st.vx[p] * st.vx[p] + st.vy[p] * st.vy[p]));
    vx[frame] = st.vx, vy[frame] = st.vy;
    if (frame == 1)
      for (std::size_t p = 0; p < vx[1].size(); ++p) vx[1][p] -= ux, vy[1][p] -= uy;
  }
  double scale = 0, change = 0, velocity = 0;
  for (std::size_t p = 0; p < dk[0].size(); ++p) {
    scale = std::max(scale, std::abs(dk[0][p]));
    change = std::max(change, std::abs(dk[1][p] - dk[0][p]));
    velocity = std::max({velocity, std::abs(vx[1][p] - vx[0][p]), std::abs(vy[1][p] - vy[0][p])});
  }
  std::printf(
      "rz %d, limiter %d: largest dK_p %.3e, its largest change with the frame %.3e (ratio %.2e); velocity %.3e\n", rz,
      limiter, scale, change, change / scale, velocity);
  return {change / scale, velocity};
}

void expect_galilean_invariant_kinetic_energy_losses(bool rz) {
  for (bool limiter : {false, true}) {
    const FrameDependence d = frame_dependence(rz, limiter);
    EXPECT_LT(d.dk, 1e-8) << "limiter " << limiter;
    EXPECT_LT(d.velocity, 1e-14) << "limiter " << limiter;
  }
}

TEST(Remap, TheFixUpsKineticEnergyLossesAreGalileanInvariant) {
  expect_galilean_invariant_kinetic_energy_losses(false);
}

TEST(RemapRz, TheFixUpsKineticEnergyLossesAreGalileanInvariant) {
  expect_galilean_invariant_kinetic_energy_losses(true);
}

TEST(Remap, SmoothVelocitySlidThereAndBackConvergesAtSecondOrder) {
  expect_second_order_velocity_remap(false);
}

TEST(RemapRz, SmoothVelocitySlidThereAndBackConvergesAtSecondOrder) {
  expect_second_order_velocity_remap(true);
}

// A velocity with jumps and a peak, remapped 15 times: the largest excursion of either
// component beyond its initial range, relative to that range.
double velocity_overshoot(bool rz, bool limiter) {
  const Mesh m = square_mesh(20);
  const std::vector<int> material(m.num_zones(), 0);
  stagger::Remapper remapper(m, material, rz);
  const auto velocity = [](double x, double y) {
    const double bump = std::hypot(x - 0.3, y - 0.6) < 0.15 ? 3.0 : 0.0;
    return std::array<double, 2>{x * ((y > 0.45 ? 2.0 : -1.0) + bump), (x > 0.55 ? 1.0 : -2.0) + 0.3 * std::sin(9 * y)};
  };
  State st = rz ? make_rz_state(
                      m, 1.0, 0.5, 0.0, [](const Mesh&, auto&, auto&, Index) { return 1.0; }, velocity)
                : make_state(
                      m, [](double x, double) { return 1.0 + 0.5 * x; }, [](double, double) { return 1.0; }, velocity);
  const auto [ulo, uhi] = std::minmax_element(st.vx.begin(), st.vx.end());
  const auto [wlo, whi] = std::minmax_element(st.vy.begin(), st.vy.end());
  const double u_lo = *ulo, u_hi = *uhi, w_lo = *wlo, w_hi = *whi;
  double worst = 0;
  std::vector<double> xo = m.x, yo = m.y, xn, yn;
  for (int step = 0; step < 15; ++step) {
    if (rz)
      moved_rz(m, 0.015, 0.7 * step, xn, yn);
    else
      moved(m, 0.015, 0.7 * step, xn, yn);
    auto f = st.fields();
    remapper.remap(xo.data(), yo.data(), xn.data(), yn.data(), f, limiter);
    xo = xn, yo = yn;
    for (Index p = 0; p < m.num_points(); ++p) {
      worst = std::max({worst, (u_lo - st.vx[p]) / (u_hi - u_lo), (st.vx[p] - u_hi) / (u_hi - u_lo),
                        (w_lo - st.vy[p]) / (w_hi - w_lo), (st.vy[p] - w_hi) / (w_hi - w_lo)});
    }
  }
  return worst;
}

// The limiter (Barth-Jespersen on the point gradients, at the midpoints of the point's edges)
// bounds the reconstruction; the new velocity, the donor's momentum after its outflows over its
// new mass, can still step a little past its neighbourhood where a point at an extreme gives
// mass away at its reconstructed (not its own) velocity: the scalar fields have a donor
// remainder bound for that (docs/ale.md), the velocities not yet. Measured: 1.7e-4 of the
// range with the limiter, 4.8e-2 and 5.0e-2 without (planar, rz); the bound asserted is 1e-3.
void expect_no_new_velocity_extrema(bool rz) {
  const double limited = velocity_overshoot(rz, true), unlimited = velocity_overshoot(rz, false);
  std::printf("rz %d: largest velocity overshoot / range: limited %.3e, unlimited %.3e\n", rz, limited, unlimited);
  EXPECT_LT(limited, 1e-3);
  EXPECT_GT(unlimited, 1e-2) << "without the limiter the remap must overshoot for the test to mean anything";
}

TEST(Remap, TheLimiterBoundsNewVelocityExtrema) {
  expect_no_new_velocity_extrema(false);
}

TEST(RemapRz, TheLimiterBoundsNewVelocityExtrema) {
  expect_no_new_velocity_extrema(true);
}

}  // namespace
