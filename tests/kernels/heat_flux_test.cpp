// The artificial heat flux kernel (docs/algorithm.md §21): zero on a uniform state, exactly
// conservative, and a 1D diffusion mode decaying at the exact discrete rate, close to the
// continuous one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "hydro/exact_sum.hpp"
#include "hydro/kernels/geometry.hpp"
#include "hydro/kernels/heat_flux.hpp"
#include "stagger/meshgen.hpp"

namespace stagger {
namespace {

// A mesh with the state arrays the kernel reads; fluid at rest unless a test sets v.
struct Case {
  Mesh mesh;
  std::vector<Index> neighbour;
  std::vector<double> vx, vy, rho, C, e, mass, kappa, cx, cy, rate;

  Case(Mesh m, bool rz) : mesh(std::move(m)) {
    const Index nz = mesh.num_zones(), np = mesh.num_points();
    neighbour = heat_flux_neighbours(mesh, std::vector<int>(nz, 0));
    vx.assign(np, 0.0), vy.assign(np, 0.0);
    rho.assign(nz, 2.0), C.assign(nz, 1.5), e.assign(nz, 1.0), mass.resize(nz);
    kappa.resize(nz), cx.resize(nz), cy.resize(nz), rate.resize(nz);
    for (Index z = 0; z < nz; ++z) {
      const Index b = mesh.zone_corner_begin[z];
      const ZoneVertices v = gather_vertices<0>(mesh.corner_point.data(), b, mesh.zone_corner_begin[z + 1] - b,
                                                mesh.x.data(), mesh.y.data());
      mass[z] = rho[z] * (rz ? RzGeometry::volume(v) : PlanarGeometry::area(v));
    }
  }
  HeatFluxInput input(double c1, double c2) const {
    return {mesh.zone_corner_begin.data(),
            mesh.corner_point.data(),
            neighbour.data(),
            mesh.x.data(),
            mesh.y.data(),
            vx.data(),
            vy.data(),
            rho.data(),
            C.data(),
            e.data(),
            mass.data(),
            c1,
            c2};
  }
  template <class Geometry>
  DtChoice rates(double c1, double c2) {
    const HeatFluxInput in = input(c1, c2);
    heat_flux_conductivity<Geometry>(in, 0, mesh.num_zones(), kappa.data(), cx.data(), cy.data());
    DtChoice choice;
    heat_flux_rates<Geometry>(in, kappa.data(), cx.data(), cy.data(), 0, mesh.num_zones(), 1.0, rate.data(), choice);
    return choice;
  }
};

Mesh perturbed_square(int n, unsigned seed) {
  Mesh m = build_mesh(meshgen::rectangle(0.5, 1.5, 0, 1, n, n));
  unsigned state = seed;
  auto next = [&state] {
    state = state * 1664525u + 1013904223u;
    return (state >> 8) / double(1u << 24) - 0.5;
  };
  std::vector<char> boundary(m.num_points(), 0);
  for (const auto& tag : m.tags)
    for (Index p : tag.points) boundary[p] = 1;
  for (Index p = 0; p < m.num_points(); ++p)
    if (!boundary[p]) m.x[p] += 0.4 / n * next(), m.y[p] += 0.4 / n * next();
  return m;
}

}  // namespace

TEST(HeatFlux, NeighboursAreMutualAndBoundariesHaveNone) {
  const Mesh m = build_mesh(meshgen::rectangle(0, 1, 0, 1, 4, 3));
  const std::vector<Index> nb = heat_flux_neighbours(m, std::vector<int>(m.num_zones(), 0));
  int interior = 0;
  for (Index z = 0; z < m.num_zones(); ++z)
    for (Index c = m.zone_corner_begin[z]; c < m.zone_corner_begin[z + 1]; ++c) {
      if (nb[c] == kNoHeatNeighbour) continue;
      ++interior;
      const Index zn = nb[c];
      EXPECT_EQ(std::count(nb.begin() + m.zone_corner_begin[zn], nb.begin() + m.zone_corner_begin[zn + 1], z), 1);
    }
  EXPECT_EQ(interior, 2 * (3 * 3 + 4 * 2));  // interior edges, seen from both sides
  // Another material across an edge: no flux there.
  std::vector<int> material(m.num_zones(), 0);
  material[0] = 1;
  const std::vector<Index> split = heat_flux_neighbours(m, material);
  for (Index c = m.zone_corner_begin[0]; c < m.zone_corner_begin[1]; ++c) EXPECT_EQ(split[c], kNoHeatNeighbour);
}

TEST(HeatFlux, ZeroOnAUniformStateOnAPerturbedMeshInBothGeometries) {
  for (bool rz : {false, true}) {
    Case k(perturbed_square(9, 7), rz);
    for (std::size_t p = 0; p < k.vx.size(); ++p) k.vx[p] = -k.mesh.x[p], k.vy[p] = 0.3 * k.mesh.y[p];
    const DtChoice dt = rz ? k.rates<RzGeometry>(1.0, 2.0) : k.rates<PlanarGeometry>(1.0, 2.0);
    for (double r : k.rate) EXPECT_EQ(r, 0.0);
    EXPECT_GT(dt.dt, 0.0);
    EXPECT_LT(dt.dt, 1.0);  // the conductances are there, only the differences vanish
  }
}

// A random energy field: every flux leaves one zone and enters the other exactly, so the
// zones' rates sum to zero up to the rounding of each zone's own sum.
TEST(HeatFlux, ExchangesAreConservativeAndFlowDownTheGradient) {
  for (bool rz : {false, true}) {
    Case k(perturbed_square(10, 3), rz);
    unsigned state = 11;
    for (double& e : k.e) state = state * 1664525u + 1013904223u, e = 1 + (state >> 8) / double(1u << 24);
    rz ? k.rates<RzGeometry>(0.7, 0.0) : k.rates<PlanarGeometry>(0.7, 0.0);
    ExactSum sum;
    double magnitude = 0;
    for (double r : k.rate) sum.add(r), magnitude += std::abs(r);
    EXPECT_GT(magnitude, 1e-3);
    EXPECT_LT(std::abs(sum.value()), 1e-14 * magnitude) << (rz ? "rz" : "planar");
    // The hottest zone loses, the coldest gains.
    const auto hot = std::max_element(k.e.begin(), k.e.end()) - k.e.begin();
    const auto cold = std::min_element(k.e.begin(), k.e.end()) - k.e.begin();
    EXPECT_LT(k.rate[hot], 0.0);
    EXPECT_GT(k.rate[cold], 0.0);
  }
}

// rz: the flux through a face is weighted by the face's radius, per radian. On a rectangle
// r in [0.5, 1.5] with e varying in z only, each zone's rate is the planar one times the
// radius of its horizontal faces (the vertical faces carry no flux), and the volume
// weighting of the masses makes the two time-step limits differ.
TEST(HeatFlux, RzFluxIsThePlanarOneTimesTheFaceRadius) {
  Case planar(build_mesh(meshgen::rectangle(0.5, 1.5, 0, 1, 5, 6)), false);
  Case rz(build_mesh(meshgen::rectangle(0.5, 1.5, 0, 1, 5, 6)), true);
  for (Index z = 0; z < planar.mesh.num_zones(); ++z) {
    const auto c = zone_centre(planar.mesh, z);
    planar.e[z] = rz.e[z] = 1 + c[1] * c[1];
  }
  planar.rates<PlanarGeometry>(0.5, 0.0);
  rz.rates<RzGeometry>(0.5, 0.0);
  for (Index z = 0; z < planar.mesh.num_zones(); ++z) {
    const double r = zone_centre(planar.mesh, z)[0];
    EXPECT_NE(planar.rate[z], 0.0);
    EXPECT_NEAR(rz.rate[z], r * planar.rate[z], 1e-13 * std::abs(planar.rate[z])) << "zone " << z;
  }
}

// 1D diffusion on an n x 1 strip with adiabatic ends: the cell-centred mode
// e = 1 + a cos(pi x / L) is an eigenvector of the discrete operator with rate
// lambda_h = (2 D / h^2) (1 - cos(pi h / L)), D = kappa / rho = c1 l C, l = h / sqrt 2 on squares.
// Forward Euler at the kernel's time-step limit: the mean is kept to round-off, the maximum
// falls monotonically, the amplitude follows (1 - dt lambda_h)^n exactly and the continuous
// exp(-D (pi/L)^2 t) within the O(h^2) of the discretisation and O(dt) of the time step.
TEST(HeatFlux, OneDimensionalModeDecaysAtTheExactRate) {
  const int n = 40;
  const double L = 1.0, h = L / n, a = 0.25, c1 = 0.8;
  Case k(build_mesh(meshgen::rectangle(0, L, 0, h, n, 1)), false);
  const auto mode = [&](Index z) { return std::cos(M_PI * zone_centre(k.mesh, z)[0] / L); };
  for (Index z = 0; z < n; ++z) k.e[z] = 1 + a * mode(z);
  const double D = c1 * (h / std::sqrt(2.0)) * k.C[0];
  const double lambda_h = 2 * D / (h * h) * (1 - std::cos(M_PI * h / L));
  ExactSum initial;
  for (Index z = 0; z < n; ++z) initial.add(k.mass[z] * k.e[z]);
  double t = 0, amplitude = a, previous_max = 1 + a;
  for (int step = 0; step < 600; ++step) {
    const DtChoice limit = k.rates<PlanarGeometry>(c1, 0.0);
    const double dt = 0.5 * limit.dt;
    for (Index z = 0; z < n; ++z) k.e[z] += dt * k.rate[z] / k.mass[z];
    t += dt;
    amplitude *= 1 - dt * lambda_h;
    const double top = *std::max_element(k.e.begin(), k.e.end());
    EXPECT_LT(top, previous_max);
    previous_max = top;
  }
  ExactSum total;
  for (Index z = 0; z < n; ++z) total.add(k.mass[z] * k.e[z]);
  EXPECT_NEAR(total.value(), initial.value(), 1e-13 * initial.value());  // 600 steps of round-off
  for (Index z = 0; z < n; ++z) EXPECT_NEAR(k.e[z], 1 + amplitude * mode(z), 1e-13) << "zone " << z;
  const double continuous = a * std::exp(-D * M_PI * M_PI / (L * L) * t);
  EXPECT_LT(amplitude, 0.5 * a);  // the mode decayed substantially
  EXPECT_NEAR(amplitude / continuous, 1.0, 5e-3);
}

}  // namespace stagger
