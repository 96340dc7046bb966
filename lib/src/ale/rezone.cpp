// The ALE rezone (docs/ale.md, "Rezone"): point-by-point minimisation of a corner-Jacobian
// smoothness functional, relaxation toward the Lagrangian mesh, and a validity guard.
#include "ale/rezone.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <string>

#include "hydro/kernels/zone_validity.hpp"
#include "stagger/error.hpp"

namespace stagger {
namespace {

// |(x, y)| without std::hypot's overflow care (slow in glibc; lengths here are mesh-sized).
[[gnu::always_inline]] inline double norm2(double x, double y) {
  return std::sqrt(x * x + y * y);
}

// Per-corner constants of the functional F = N / D (docs/ale.md, "Rezone"):
// with A = [u v] the corner's edge matrix (u to the next vertex, v to the previous one) and
// M the inverse of the target corner W, J = A M, |J|^2 = tr(A^T A K) with K = M M^T, and
// det J = det A det M.
struct CornerTarget {
  double k11 = 1, k12 = 0, k22 = 1, det_m = 1;
};

// The target of a regular m-gon's corner (unit edges, interior angle (m-2) pi / m): W =
// [[1, c], [0, s]], M = W^-1 = [[1, -c/s], [0, 1/s]]. Quads get K = I exactly.
CornerTarget regular_target(int m) {
  if (m == 4) return {};
  const double alpha = (m - 2) * std::numbers::pi / m;
  const double c = std::cos(alpha), s = std::sin(alpha);
  return {1 + c * c / (s * s), -c / (s * s), 1 / (s * s), 1 / s};
}

// The target of a reference corner with edges u (to next) and v (to previous): M = [u v]^-1.
// A corner that is not strictly convex in the reference falls back to the regular polygon's.
CornerTarget reference_target(double ux, double uy, double vx, double vy, int m) {
  const double det = ux * vy - uy * vx;
  if (!(det > 0)) return regular_target(m);
  // M = 1/det [[vy, -vx], [-uy, ux]]; K = M M^T.
  const double m11 = vy / det, m12 = -vx / det, m21 = -uy / det, m22 = ux / det;
  return {m11 * m11 + m12 * m12, m11 * m21 + m12 * m22, m21 * m21 + m22 * m22, 1 / det};
}

// N = k11 |u|^2 + 2 k12 u.v + k22 |v|^2 and D = det_m (u x v) of one corner.
struct CornerValue {
  double n, d;
};
[[gnu::always_inline]] inline CornerValue corner_value(const CornerTarget& t, double ux, double uy, double vx,
                                                       double vy) {
  return {t.k11 * (ux * ux + uy * uy) + 2 * t.k12 * (ux * vx + uy * vy) + t.k22 * (vx * vx + vy * vy),
          t.det_m * (ux * vy - uy * vx)};
}

// The barrier denominator. delta = 0: D itself. delta > 0: the regularised
// h(D) = (D + sqrt(D^2 + 4 delta^2)) / 2 of Escobar et al. (2003), positive for any D, so that
// a non-convex or inverted corner has a finite functional that decreases as it opens up.
struct Denominator {
  double h, dh, d2h;
};
[[gnu::always_inline]] inline Denominator denominator(double d, double delta) {
  if (delta == 0) return {d, 1, 0};
  const double r = std::sqrt(d * d + 4 * delta * delta);
  return {0.5 * (d + r), 0.5 * (1 + d / r), 2 * delta * delta / (r * r * r)};
}

// The local problem of one point: the corners whose Jacobian depends on it.
struct LocalCorner {
  Index p0, p1, p2;  // corner vertex, next, previous
  CornerTarget target;
  double alpha, beta;  // du = alpha dp, dv = beta dp
};

constexpr int kMaxLocal = 64;

struct LocalProblem {
  int count = 0;
  LocalCorner c[kMaxLocal];
};

// Functional value over the local corners with `p` at (px, py); +inf if a denominator is not
// positive (only possible with delta = 0).
double local_value(const LocalProblem& lp, Index p, double px, double py, const double* x, const double* y,
                   double delta, double w = 0, double tau = 1) {
  double f = 0;
  for (int i = 0; i < lp.count; ++i) {
    const LocalCorner& c = lp.c[i];
    const double x0 = c.p0 == p ? px : x[c.p0], y0 = c.p0 == p ? py : y[c.p0];
    const double x1 = c.p1 == p ? px : x[c.p1], y1 = c.p1 == p ? py : y[c.p1];
    const double x2 = c.p2 == p ? px : x[c.p2], y2 = c.p2 == p ? py : y[c.p2];
    const CornerValue v = corner_value(c.target, x1 - x0, y1 - y0, x2 - x0, y2 - y0);
    const double h = denominator(v.d, delta).h;
    if (!(h > 0)) return std::numeric_limits<double>::infinity();
    // Size term w (D / tau + tau / h(D)): the tau / h part shares the shape term's denominator.
    f += (v.n + w * tau) / h + w * v.d / tau;
  }
  return f;
}

// Gradient and Hessian of the local functional with respect to p. Because u and v move by
// multiples of the same dp, the second derivative of D along dp vanishes (dp x dp = 0).
void local_derivatives(const LocalProblem& lp, const double* x, const double* y, double delta, double w, double tau,
                       Eigen::Vector2d& g, Eigen::Matrix2d& h) {
  g.setZero();
  h.setZero();
  for (int i = 0; i < lp.count; ++i) {
    const LocalCorner& c = lp.c[i];
    const double ux = x[c.p1] - x[c.p0], uy = y[c.p1] - y[c.p0];
    const double vx = x[c.p2] - x[c.p0], vy = y[c.p2] - y[c.p0];
    const CornerTarget& t = c.target;
    CornerValue v = corner_value(t, ux, uy, vx, vy);
    const Denominator den = denominator(v.d, delta);
    const double a = c.alpha, b = c.beta;
    // The size term adds the constant w tau to the numerator and w D / tau, linear in p.
    const double linear = w / tau;
    v.n += w * tau;
    // dN/dp = a dN/du + b dN/dv; dN/du = 2 (k11 u + k12 v), dN/dv = 2 (k12 u + k22 v).
    const Eigen::Vector2d gn(2 * (a * (t.k11 * ux + t.k12 * vx) + b * (t.k12 * ux + t.k22 * vx)),
                             2 * (a * (t.k11 * uy + t.k12 * vy) + b * (t.k12 * uy + t.k22 * vy)));
    // dD/du = det_m (vy, -vx), dD/dv = det_m (-uy, ux).
    const Eigen::Vector2d gd(t.det_m * (a * vy - b * uy), t.det_m * (-a * vx + b * ux));
    const double hn = 2 * (a * a * t.k11 + 2 * a * b * t.k12 + b * b * t.k22);
    const Eigen::Vector2d gh = den.dh * gd;
    const double inv = 1 / den.h;
    g += inv * gn - (v.n * inv * inv) * gh + linear * gd;
    h += (hn * inv) * Eigen::Matrix2d::Identity() - (inv * inv) * (gn * gh.transpose() + gh * gn.transpose()) +
         (2 * v.n * inv * inv * inv) * (gh * gh.transpose()) - (v.n * inv * inv * den.d2h) * (gd * gd.transpose());
  }
}

// Zone z at positions (x, y), with optionally point p replaced by (px, py).
ZoneVertices zone_vertices(const Mesh& mesh, Index z, const double* x, const double* y, Index p = -1, double px = 0,
                           double py = 0) {
  const Index b = mesh.zone_corner_begin[z];
  const int n = static_cast<int>(mesh.zone_corner_begin[z + 1] - b);
  ZoneVertices v;
  v.n = n;
  for (int k = 0; k < n; ++k) {
    const Index q = mesh.corner_point[b + k];
    v.x[k] = q == p ? px : x[q];
    v.y[k] = q == p ? py : y[q];
  }
  return v;
}

// The weighted sums S_k of a stencil; N > 0 fixes the neighbour count at compile time.
// The x and y sums side by side (s[2k], s[2k + 1]), so that each weight multiplies both
// coordinates in one vector operation: the same products and sums, lane by lane.
template <int N>
[[gnu::always_inline]] inline void stencil_sums(const Index* points, int n, const double* w, const double* xs,
                                                const double* ys, double* sx, double* sy) {
  double s[10] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  for (int i = 0; i < (N ? N : n); ++i) {
    const double xq = xs[points[i]], yq = ys[points[i]];
    for (int k = 0; k < 5; ++k) {
      s[2 * k] += w[5 * i + k] * xq;
      s[2 * k + 1] += w[5 * i + k] * yq;
    }
  }
  for (int k = 0; k < 5; ++k) sx[k] += s[2 * k], sy[k] += s[2 * k + 1];
}

// One Gauss-Seidel update of point p by the Winslow equations (docs/ale.md, "Rezone"):
// with the one-ring's least-squares derivatives x_k = S_k - s_k x_0 (S_k the weighted sum over
// the neighbours, s_k the weights' sum), the equation alpha x_xixi - 2 beta x_xieta +
// gamma x_etaeta = 0 with the coefficients frozen at the current position is linear in x_0.
// Interior points go to its solution; slide points to its projection on their boundary edge.
void winslow_point(const RezoneConstraints& rc, Index p, RezonePointKind kind, const double* ea, const double* eb,
                   double la, double lb, double lim, double x_lag, double y_lag, double* xs, double* ys, double& arc) {
  const Index id = rc.stencil_id[p];
  if (id < 0) return;
  const Index b = rc.stencil_begin[p];
  const int n = static_cast<int>(rc.stencil_begin[p + 1] - b);
  const double* w = rc.stencil_weights.data() + rc.weights_begin[id];
  double sx[5] = {0, 0, 0, 0, 0}, sy[5] = {0, 0, 0, 0, 0};
  if (n == 8) {
    stencil_sums<8>(rc.stencil_points.data() + b, 8, w, xs, ys, sx, sy);  // interior point of a quad mesh
  } else {
    stencil_sums<0>(rc.stencil_points.data() + b, n, w, xs, ys, sx, sy);
  }
  const double* r = w + 5 * n;
  const double x0 = xs[p], y0 = ys[p];
  const double x_xi = sx[3] - r[3] * x0, x_eta = sx[4] - r[4] * x0;
  const double y_xi = sy[3] - r[3] * y0, y_eta = sy[4] - r[4] * y0;
  const double alpha = x_eta * x_eta + y_eta * y_eta, beta = x_xi * x_eta + y_xi * y_eta,
               gamma = x_xi * x_xi + y_xi * y_xi;
  const double den = alpha * r[0] - 2 * beta * r[1] + gamma * r[2];
  if (!(den > 1e-12 * (alpha + gamma) * (std::abs(r[0]) + std::abs(r[2])))) return;
  const double tx = (alpha * sx[0] - 2 * beta * sx[1] + gamma * sx[2]) / den;
  const double ty = (alpha * sy[0] - 2 * beta * sy[1] + gamma * sy[2]) / den;
  if (kind == RezonePointKind::interior) {
    double dx = tx - x_lag, dy = ty - y_lag;
    const double dist = norm2(dx, dy);
    if (dist > lim) {
      dx *= lim / dist;
      dy *= lim / dist;
    }
    // Converged points stay bitwise (a uniform mesh is a fixed point, not a round-off walk).
    if (!(norm2(x_lag + dx - x0, y_lag + dy - y0) > 1e-12 * lim)) return;
    xs[p] = x_lag + dx;
    ys[p] = y_lag + dy;
    return;
  }
  // Slide: arc length sigma >= 0 along e_b, < 0 along e_a; the move from the current point
  // toward the target, projected on the edge it would run along, stopping at the kink.
  const double s_b = (tx - x0) * eb[0] + (ty - y0) * eb[1];
  const double s_a = (tx - x0) * ea[0] + (ty - y0) * ea[1];
  double sigma = arc;
  if (sigma > 0 || (sigma == 0 && s_b > 0)) {
    sigma = std::max(sigma + s_b, 0.0);
  } else if (sigma < 0 || s_a > 0) {
    sigma = std::min(sigma - s_a, 0.0);
  }
  sigma = std::clamp(sigma, -std::min(0.45 * la, lim), std::min(0.45 * lb, lim));
  if (!(std::abs(sigma - arc) > 1e-12 * lim)) return;
  arc = sigma;
  if (sigma >= 0) {
    xs[p] = x_lag + sigma * eb[0];
    ys[p] = y_lag + sigma * eb[1];
  } else {
    xs[p] = x_lag - sigma * ea[0];
    ys[p] = y_lag - sigma * ea[1];
  }
}

void check_options(const RezoneOptions& o) {
  if (!(o.relaxation >= 0 && o.relaxation <= 1))
    throw Error("rezone: relaxation = " + std::to_string(o.relaxation) + " is outside [0, 1]");
  if (o.iterations < 0) throw Error("rezone: iterations = " + std::to_string(o.iterations) + " is negative");
  if (!(o.corner_angle_degrees >= 0 && o.corner_angle_degrees < 90))
    throw Error("rezone: corner_angle_degrees = " + std::to_string(o.corner_angle_degrees) + " is outside [0, 90)");
  if (!(o.max_move > 0 && o.max_move <= 1))
    throw Error("rezone: max_move = " + std::to_string(o.max_move) + " is outside (0, 1]");
  if (!(o.size_weight >= 0 && std::isfinite(o.size_weight)))
    throw Error("rezone: size_weight = " + std::to_string(o.size_weight) + " is not a finite number >= 0");
}

void check_size(std::span<const double> s, Index n, const char* name, const Mesh& mesh) {
  if (static_cast<Index>(s.size()) != n)
    throw Error("rezone: " + std::string(name) + " has " + std::to_string(s.size()) + " entries, the mesh " +
                mesh.source + " has " + std::to_string(n) + " points");
}

// The Winslow stencil of one point (Knupp 1999): its zones in counter-clockwise order, each
// given an equal sector of the logical plane (2 pi / k around an interior point, pi / k at a
// boundary point); a zone's two edge neighbours sit on the sector's sides at unit distance,
// its other vertices where a regular polygon with that corner puts them (u + v for a quad).
// Returns false if the zones do not form one fan (then the point gets no stencil).
bool winslow_fan(const Mesh& mesh, Index p, std::vector<Index>& points, std::vector<double>& xi,
                 std::vector<double>& eta, std::vector<int>& key) {
  struct Fan {
    Index corner, u, v;
    int m;
  };
  Fan fan[64];
  const Index cb = mesh.point_corner_begin[p], ce = mesh.point_corner_begin[p + 1];
  const int k = static_cast<int>(ce - cb);
  if (k == 0 || k > 64) return false;
  for (int i = 0; i < k; ++i) {
    const Index c = mesh.point_corners[cb + i], z = mesh.corner_zone[c];
    const Index b = mesh.zone_corner_begin[z], e = mesh.zone_corner_begin[z + 1];
    fan[i] = {c, mesh.corner_point[c + 1 == e ? b : c + 1], mesh.corner_point[c == b ? e - 1 : c - 1],
              static_cast<int>(e - b)};
    if (e - b > kMaxZoneVertices) return false;
  }
  // The first zone of an open fan is the one whose u no other zone has as v.
  int start = 0;
  bool closed = true;
  for (int i = 0; i < k && closed; ++i) {
    bool found = false;
    for (int j = 0; j < k; ++j) found = found || fan[j].v == fan[i].u;
    if (!found) {
      start = i;
      closed = false;
    }
  }
  int order[64];
  order[0] = start;
  for (int t = 1; t < k; ++t) {
    order[t] = -1;
    for (int j = 0; j < k; ++j)
      if (fan[j].u == fan[order[t - 1]].v) order[t] = j;
    if (order[t] < 0) return false;
  }
  if (closed && fan[order[k - 1]].v != fan[order[0]].u) return false;
  const double phi = (closed ? 2 : 1) * std::numbers::pi / k;
  points.clear();
  xi.clear();
  eta.clear();
  key.assign(1, closed ? 1 : 0);
  // Logical offsets that are integers up to rounding (the quad fans: cos(pi/2)) are made
  // exact, so that the weights reproduce a uniform mesh to the last bit where they can.
  const auto snap = [](double v) { return std::abs(v - std::round(v)) < 1e-12 ? std::round(v) : v; };
  const auto add = [&](Index q, double a, double b) {
    a = snap(a);
    b = snap(b);
    points.push_back(q);
    xi.push_back(a);
    eta.push_back(b);
  };
  for (int t = 0; t < k; ++t) {
    const Fan& f = fan[order[t]];
    key.push_back(f.m);
    const double ux = std::cos(t * phi), uy = std::sin(t * phi);
    const double vx = std::cos((t + 1) * phi), vy = std::sin((t + 1) * phi);
    add(f.u, ux, uy);
    const Index z = mesh.corner_zone[f.corner], b = mesh.zone_corner_begin[z];
    if (f.m == 4) {
      add(mesh.corner_point[b + (f.corner - b + 2) % 4], ux + vx, uy + vy);
    } else if (f.m > 4) {
      // Regular m-gon with vertex 0 at the origin, vertex 1 at (1, 0), counter-clockwise;
      // the linear map taking its corner edges to (u, v) places the other vertices.
      const double ext = 2 * std::numbers::pi / f.m, alpha = std::numbers::pi - ext;
      const double ca = std::cos(alpha), sa = std::sin(alpha);
      double rx = 1, ry = 0;
      for (int j = 2; j <= f.m - 2; ++j) {
        rx += std::cos((j - 1) * ext);
        ry += std::sin((j - 1) * ext);
        // (rx, ry) = a e1 + c (ca, sa)  ->  a u + c v.
        const double c = ry / sa, a = rx - c * ca;
        add(mesh.corner_point[b + (f.corner - b + j) % f.m], a * ux + c * vx, a * uy + c * vy);
      }
    }
    if (!closed && t == k - 1) add(f.v, vx, vy);
  }
  return true;
}

// Least-squares derivative weights of a logical layout: x_i - x_0 ~ a x_xi + b x_eta +
// a^2/2 x_xixi + a b x_xieta + b^2/2 x_etaeta. A small penalty on the second derivatives
// makes under-determined fans (few neighbours) solvable and leaves linear maps exact (their
// second derivatives are zero, so the penalty costs nothing there).
// Returns false (no weights appended) if the first derivatives are not determined: a fan whose
// logical neighbours lie on one line (a point in the middle of a straight side of its only zone).
bool winslow_weights(const std::vector<double>& xi, const std::vector<double>& eta, std::vector<double>& out) {
  const int n = static_cast<int>(xi.size());
  Eigen::MatrixXd a(n, 5);
  for (int i = 0; i < n; ++i) a.row(i) << xi[i], eta[i], 0.5 * xi[i] * xi[i], xi[i] * eta[i], 0.5 * eta[i] * eta[i];
  Eigen::Matrix<double, 5, 5> m = a.transpose() * a;
  for (int k = 2; k < 5; ++k) m(k, k) += 1e-4;
  const Eigen::LDLT<Eigen::Matrix<double, 5, 5>> ldlt(m);
  const auto d = ldlt.vectorD();
  if (ldlt.info() != Eigen::Success || !(d.minCoeff() > 1e-10 * d.maxCoeff())) return false;
  const Eigen::MatrixXd pinv = ldlt.solve(a.transpose());  // 5 x n
  if (!pinv.allFinite()) return false;
  // Stored per neighbour as (xixi, xieta, etaeta, xi, eta), then the row sums.
  const int row[5] = {2, 3, 4, 0, 1};
  double sum[5] = {0, 0, 0, 0, 0};
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 5; ++k) {
      out.push_back(pinv(row[k], i));
      sum[k] += pinv(row[k], i);
    }
  for (int k = 0; k < 5; ++k) out.push_back(sum[k]);
  return true;
}

}  // namespace

RezoneConstraints make_rezone_constraints(const Mesh& mesh, std::span<const BoundaryCondition> boundaries,
                                          std::span<const Index> zone_material, WinslowLayout layout) {
  const Index np = mesh.num_points(), nz = mesh.num_zones();
  if (!zone_material.empty() && static_cast<Index>(zone_material.size()) != nz)
    throw Error("rezone constraints: zone_material has " + std::to_string(zone_material.size()) +
                " entries, the mesh " + mesh.source + " has " + std::to_string(nz) + " zones");
  const auto material = [&](Index z) { return zone_material.empty() ? mesh.zone_region[z] : zone_material[z]; };

  RezoneConstraints rc;
  rc.kind.assign(np, RezonePointKind::interior);
  rc.boundary_neighbours.assign(np, {-1, -1});
  std::vector<std::uint8_t> fixed(np, 0);

  // Boundary edges: sides that no other zone has (in the opposite direction).
  std::vector<std::uint64_t> keys;
  keys.reserve(mesh.num_corners());
  for (Index z = 0; z < nz; ++z) {
    const Index b = mesh.zone_corner_begin[z], e = mesh.zone_corner_begin[z + 1];
    if (e - b > kMaxZoneVertices) {
      for (Index c = b; c < e; ++c) fixed[mesh.corner_point[c]] = 1;
    }
    for (Index c = b; c < e; ++c) {
      const Index p = mesh.corner_point[c], q = mesh.corner_point[c + 1 == e ? b : c + 1];
      keys.push_back((std::uint64_t(std::min(p, q)) << 32) | std::uint64_t(std::max(p, q)));
    }
  }
  std::sort(keys.begin(), keys.end());
  std::vector<int> boundary_edges(np, 0);
  for (std::size_t i = 0; i < keys.size();) {
    std::size_t j = i;
    while (j < keys.size() && keys[j] == keys[i]) ++j;
    if (j - i == 1) {
      const Index p = Index(keys[i] >> 32), q = Index(keys[i] & 0xffffffffu);
      for (const auto& [a, o] : {std::pair{p, q}, std::pair{q, p}}) {
        const int k = boundary_edges[a]++;
        if (k < 2) rc.boundary_neighbours[a][k] = o;
      }
    }
    i = j;
  }

  // Tags: points on two or more tags, and points of periodic tags, stay.
  std::vector<std::uint8_t> tag_count(np, 0);
  for (const BoundaryTag& tag : mesh.tags) {
    bool periodic = false;
    for (const BoundaryCondition& bc : boundaries)
      if (bc.tag == tag.name && bc.kind == BoundaryKind::periodic) periodic = true;
    for (const BoundaryCondition& bc : boundaries)
      if (bc.partner == tag.name && bc.kind == BoundaryKind::periodic) periodic = true;
    for (const Index p : tag.points) {
      if (tag_count[p] < 255) ++tag_count[p];
      if (periodic) fixed[p] = 1;
    }
  }

  for (Index p = 0; p < np; ++p) {
    // Material interface: the point's zones do not all share one material.
    const Index cb = mesh.point_corner_begin[p], ce = mesh.point_corner_begin[p + 1];
    for (Index i = cb; i < ce; ++i)
      if (material(mesh.corner_zone[mesh.point_corners[i]]) != material(mesh.corner_zone[mesh.point_corners[cb]]))
        fixed[p] = 1;
    if (ce == cb) fixed[p] = 1;
    if (tag_count[p] >= 2) fixed[p] = 1;
    if (boundary_edges[p] == 0) {
      // A tag on an interior curve: keep its points where they are.
      if (tag_count[p] > 0) fixed[p] = 1;
    } else if (boundary_edges[p] != 2) {
      fixed[p] = 1;  // a pinch point of the boundary
    }
    if (fixed[p]) {
      rc.kind[p] = RezonePointKind::fixed;
      rc.boundary_neighbours[p] = {-1, -1};
      ++rc.num_fixed;
    } else if (boundary_edges[p] == 2) {
      rc.kind[p] = RezonePointKind::slide;
      ++rc.num_slide;
    } else {
      rc.boundary_neighbours[p] = {-1, -1};
      ++rc.num_interior;
    }
  }

  // Winslow stencils of the points that may move; fans with the same zone sizes share weights.
  rc.stencil_id.assign(np, -1);
  rc.stencil_begin.assign(1, 0);
  std::map<std::vector<int>, Index> known;
  std::map<std::vector<double>, Index> known_reference;
  std::vector<Index> fan_points;
  std::vector<double> xi, eta, offsets;
  std::vector<int> key;
  // known: layout -> weight set, or -1 for a fan without usable weights.
  const auto weights_of = [&](auto& table, const auto& k) {
    auto it = table.find(k);
    if (it == table.end()) {
      const bool ok = winslow_weights(xi, eta, rc.stencil_weights);
      const Index id = ok ? static_cast<Index>(rc.weights_begin.size()) - 1 : -1;
      if (ok) rc.weights_begin.push_back(static_cast<Index>(rc.stencil_weights.size()));
      it = table.emplace(k, id).first;
    }
    return it->second;
  };
  for (Index p = 0; p < np; ++p) {
    if (rc.kind[p] != RezonePointKind::fixed && winslow_fan(mesh, p, fan_points, xi, eta, key)) {
      if (layout == WinslowLayout::regular) {
        rc.stencil_id[p] = weights_of(known, key);  // fans with the same zone sizes share weights
      } else {
        // The initial offsets in units of the mean initial edge (the edge neighbours are the
        // regular layout's points at unit distance). Offsets that are integers to rounding are
        // made exact, so that the points of a uniform mesh share one weight set.
        double length = 0;
        int edges = 0;
        for (std::size_t i = 0; i < fan_points.size(); ++i)
          if (std::abs(xi[i] * xi[i] + eta[i] * eta[i] - 1) < 1e-9) {
            length += norm2(mesh.x[fan_points[i]] - mesh.x[p], mesh.y[fan_points[i]] - mesh.y[p]);
            ++edges;
          }
        length /= std::max(edges, 1);
        const auto snap = [](double v) { return std::abs(v - std::round(v)) < 1e-9 ? std::round(v) : v; };
        offsets.assign(1, key[0]);
        for (std::size_t i = 0; i < fan_points.size(); ++i) {
          xi[i] = snap((mesh.x[fan_points[i]] - mesh.x[p]) / length);
          eta[i] = snap((mesh.y[fan_points[i]] - mesh.y[p]) / length);
          offsets.push_back(xi[i]);
          offsets.push_back(eta[i]);
        }
        rc.stencil_id[p] = length > 0 ? weights_of(known_reference, offsets) : -1;
      }
      if (rc.stencil_id[p] >= 0)
        rc.stencil_points.insert(rc.stencil_points.end(), fan_points.begin(), fan_points.end());
    }
    rc.stencil_begin.push_back(static_cast<Index>(rc.stencil_points.size()));
  }

  // Greedy colouring of the points that may move: no two points of one colour share a zone.
  std::vector<int> colour(np, -1);
  std::vector<Index> seen;  // seen[c] == p: colour c is taken by a zone neighbour of p
  int colours = 0;
  for (Index p = 0; p < np; ++p) {
    if (rc.kind[p] == RezonePointKind::fixed) continue;
    for (Index i = mesh.point_corner_begin[p]; i < mesh.point_corner_begin[p + 1]; ++i) {
      const Index z = mesh.corner_zone[mesh.point_corners[i]];
      for (Index c = mesh.zone_corner_begin[z]; c < mesh.zone_corner_begin[z + 1]; ++c) {
        const int k = colour[mesh.corner_point[c]];
        if (k >= 0) seen[k] = p;
      }
    }
    int k = 0;
    while (k < colours && seen[k] == p) ++k;
    if (k == colours) {
      ++colours;
      seen.push_back(-1);
    }
    colour[p] = k;
  }
  rc.colour_begin.assign(colours + 1, 0);
  for (Index p = 0; p < np; ++p)
    if (colour[p] >= 0) ++rc.colour_begin[colour[p] + 1];
  for (int k = 0; k < colours; ++k) rc.colour_begin[k + 1] += rc.colour_begin[k];
  rc.colour_points.resize(rc.colour_begin[colours]);
  std::vector<Index> fill(rc.colour_begin.begin(), rc.colour_begin.end() - 1);
  for (Index p = 0; p < np; ++p)
    if (colour[p] >= 0) rc.colour_points[fill[colour[p]]++] = p;
  return rc;
}

RezoneResult rezone(const Mesh& mesh, const RezoneConstraints& rc, const RezoneOptions& options,
                    std::span<const double> x_lag, std::span<const double> y_lag, std::span<const double> x_ref,
                    std::span<const double> y_ref, std::span<double> x_new, std::span<double> y_new,
                    RezoneWorkspace& ws) {
  check_options(options);
  const Index np = mesh.num_points(), nz = mesh.num_zones();
  check_size(x_lag, np, "x_lag", mesh);
  check_size(y_lag, np, "y_lag", mesh);
  check_size({x_new.data(), x_new.size()}, np, "x_new", mesh);
  check_size({y_new.data(), y_new.size()}, np, "y_new", mesh);
  if (np > 0 && (x_new.data() == x_lag.data() || y_new.data() == y_lag.data()))
    throw Error(
        "rezone: x_new/y_new must be other arrays than x_lag/y_lag (the Lagrangian positions are read to the end)");
  if (static_cast<Index>(rc.kind.size()) != np)
    throw Error("rezone: the constraints were built for " + std::to_string(rc.kind.size()) + " points, the mesh " +
                mesh.source + " has " + std::to_string(np));
  const bool use_reference = options.method == RezoneMethod::reference_jacobian;
  if (use_reference) {
    check_size(x_ref, np, "x_ref", mesh);
    check_size(y_ref, np, "y_ref", mesh);
  }

  RezoneResult result;
  std::copy(x_lag.begin(), x_lag.end(), x_new.begin());
  std::copy(y_lag.begin(), y_lag.end(), y_new.begin());
  if (options.relaxation == 0 || options.iterations == 0) return result;

  const Index nc = mesh.num_corners();
  ws.xs.assign(x_lag.begin(), x_lag.end());
  ws.ys.assign(y_lag.begin(), y_lag.end());
  ws.arc.assign(np, 0.0);
  ws.move_limit.resize(np);
  if (use_reference) {
    // Corner targets (x_ref is constant, but recomputing keeps the call pure; O(corners)).
    ws.target.resize(4 * static_cast<std::size_t>(nc));
    for (Index z = 0; z < nz; ++z) {
      const Index b = mesh.zone_corner_begin[z], e = mesh.zone_corner_begin[z + 1];
      const int m = static_cast<int>(e - b);
      for (Index c = b; c < e; ++c) {
        const Index p0 = mesh.corner_point[c], p1 = mesh.corner_point[c + 1 == e ? b : c + 1],
                    p2 = mesh.corner_point[c == b ? e - 1 : c - 1];
        const CornerTarget t = reference_target(x_ref[p1] - x_ref[p0], y_ref[p1] - y_ref[p0], x_ref[p2] - x_ref[p0],
                                                y_ref[p2] - y_ref[p0], m);
        ws.target[4 * c] = t.k11;
        ws.target[4 * c + 1] = t.k12;
        ws.target[4 * c + 2] = t.k22;
        ws.target[4 * c + 3] = t.det_m;
      }
    }
  }
  // Each point moves at most max_move times its shortest Lagrangian edge (a gather over the
  // point's corners, so the loop is parallel). The bound is on the final, relaxed move: the
  // smoothed move may be 1 / relaxation times longer (up to one edge). Capping the smoothed
  // move instead leaves relaxation * max_move of an edge per remap, and where the flow closes
  // an edge (a shock reflecting off a wall) the rezone then cannot reopen it as fast as the
  // flow shuts it: the cap shrinks with the edge and the zone collapses (docs/ale.md).
  const double limit_factor = std::min(options.max_move / options.relaxation, 1.0);
#pragma omp parallel for schedule(static) if (np > 20000)
  for (Index p = 0; p < np; ++p) {
    double shortest2 = std::numeric_limits<double>::infinity();
    if (rc.kind[p] != RezonePointKind::fixed) {
      // An interior point has no boundary edge: each of its edges belongs to two zones, run
      // once each way (the zones are all counter-clockwise), so its next points are all its
      // neighbours and its previous points the same again. The minimum is then the same.
      const bool closed = rc.kind[p] == RezonePointKind::interior;
      const double xp = x_lag[p], yp = y_lag[p];
      for (Index i = mesh.point_corner_begin[p]; i < mesh.point_corner_begin[p + 1]; ++i) {
        const Index c = mesh.point_corners[i], z = mesh.corner_zone[c];
        const Index b = mesh.zone_corner_begin[z], e = mesh.zone_corner_begin[z + 1];
        const Index next = mesh.corner_point[c + 1 == e ? b : c + 1];
        const double nx = x_lag[next] - xp, ny = y_lag[next] - yp;
        shortest2 = std::min(shortest2, nx * nx + ny * ny);
        if (closed) continue;
        const Index prev = mesh.corner_point[c == b ? e - 1 : c - 1];
        const double px = x_lag[prev] - xp, py = y_lag[prev] - yp;
        shortest2 = std::min(shortest2, px * px + py * py);
      }
    }
    ws.move_limit[p] = limit_factor * std::sqrt(shortest2);
  }

  // Slide points this call: the boundary turns by at most corner_angle at the Lagrangian
  // positions. Directions e_a, e_b toward the two boundary neighbours; lengths bound the slide.
  const double cos_corner = std::cos(options.corner_angle_degrees * std::numbers::pi / 180);
  const auto slide_geometry = [&](Index p, double* ea, double* eb, double* la, double* lb) {
    const auto [a, b] = rc.boundary_neighbours[p];
    const double ax = x_lag[a] - x_lag[p], ay = y_lag[a] - y_lag[p];
    const double bx = x_lag[b] - x_lag[p], by = y_lag[b] - y_lag[p];
    *la = norm2(ax, ay);
    *lb = norm2(bx, by);
    if (!(*la > 0 && *lb > 0)) return false;
    ea[0] = ax / *la, ea[1] = ay / *la, eb[0] = bx / *lb, eb[1] = by / *lb;
    return -(ea[0] * eb[0] + ea[1] * eb[1]) >= cos_corner;
  };

  double* xs = ws.xs.data();
  double* ys = ws.ys.data();
  // One point's update. Points of one colour share no zone (make_rezone_constraints), so
  // they are independent: a colour is one parallel loop, and the result does not depend on
  // the number of threads.
  const auto update = [&](Index p) {
    const RezonePointKind kind = rc.kind[p];
    if (kind == RezonePointKind::fixed) return;
    double ea[2] = {0, 0}, eb[2] = {0, 0}, la = 0, lb = 0;
    if (kind == RezonePointKind::slide && !slide_geometry(p, ea, eb, &la, &lb)) return;
    if (!use_reference) {
      winslow_point(rc, p, kind, ea, eb, la, lb, ws.move_limit[p], x_lag[p], y_lag[p], xs, ys, ws.arc[p]);
      return;
    }

    // The corners around p: in each zone, the corner at p and its two neighbours.
    LocalProblem lp;
    lp.count = 0;
    double dmin = std::numeric_limits<double>::infinity(), dmax = 0, dsum = 0;
    const Index cb = mesh.point_corner_begin[p], ce = mesh.point_corner_begin[p + 1];
    bool too_many = false;
    for (Index i = cb; i < ce && !too_many; ++i) {
      const Index cp = mesh.point_corners[i], z = mesh.corner_zone[cp];
      const Index b = mesh.zone_corner_begin[z], e = mesh.zone_corner_begin[z + 1];
      const Index prev = cp == b ? e - 1 : cp - 1, next = cp + 1 == e ? b : cp + 1;
      for (const Index c : {prev, cp, next}) {
        if (lp.count == kMaxLocal) {
          too_many = true;
          break;
        }
        LocalCorner& l = lp.c[lp.count++];
        l.p0 = mesh.corner_point[c];
        l.p1 = mesh.corner_point[c + 1 == e ? b : c + 1];
        l.p2 = mesh.corner_point[c == b ? e - 1 : c - 1];
        l.target = {ws.target[4 * c], ws.target[4 * c + 1], ws.target[4 * c + 2], ws.target[4 * c + 3]};
        l.alpha = c == cp ? -1.0 : (c == prev ? 1.0 : 0.0);
        l.beta = c == cp ? -1.0 : (c == next ? 1.0 : 0.0);
        const double d =
            corner_value(l.target, xs[l.p1] - xs[l.p0], ys[l.p1] - ys[l.p0], xs[l.p2] - xs[l.p0], ys[l.p2] - ys[l.p0])
                .d;
        dmin = std::min(dmin, d);
        dmax = std::max(dmax, std::abs(d));
        dsum += d;
      }
    }
    if (too_many || !(dmax > 0)) return;
    // Regularise only where a corner is not convex (then the plain functional has no barrier).
    const double delta = dmin > 0 ? 0.0 : 1e-2 * dmax;
    // Size target: the mean relative corner area around p, frozen for this update (a reference
    // mesh, or any uniform scaling of it, has D = tau everywhere: still a fixed point).
    const double tau = dsum / lp.count;
    const double w = tau > 0 ? options.size_weight : 0.0;

    Eigen::Vector2d g;
    Eigen::Matrix2d h;
    local_derivatives(lp, xs, ys, delta, w, tau, g, h);
    const double px = xs[p], py = ys[p];
    const double f0 = local_value(lp, p, px, py, xs, ys, delta, w, tau);
    const double lim = ws.move_limit[p];

    // Candidate position as a function of the step fraction t in (0, 1].
    double sx = 0, sy = 0;  // interior: full step
    double sigma0 = ws.arc[p], sigma1 = sigma0;
    if (kind == RezonePointKind::interior) {
      Eigen::Matrix2d hs = h;
      const double tr = h.trace();
      const double disc = std::sqrt(0.25 * (h(0, 0) - h(1, 1)) * (h(0, 0) - h(1, 1)) + h(0, 1) * h(0, 1));
      const double lmin = 0.5 * tr - disc, lmax = 0.5 * tr + disc;
      if (!(lmin > 1e-8 * std::abs(lmax)))
        hs += (std::abs(lmin) + 1e-3 * std::abs(lmax) + 1e-300) * Eigen::Matrix2d::Identity();
      const Eigen::Vector2d step = hs.llt().solve(-g);
      sx = step(0);
      sy = step(1);
      // Keep within the move limit around the Lagrangian position.
      const double dx = px + sx - x_lag[p], dy = py + sy - y_lag[p];
      const double dist = norm2(dx, dy);
      if (dist > lim) {
        sx = x_lag[p] + dx * (lim / dist) - px;
        sy = y_lag[p] + dy * (lim / dist) - py;
      }
      if (!(norm2(sx, sy) > 1e-10 * lim)) return;
    } else {
      // Along the old boundary: arc length sigma >= 0 toward b, < 0 toward a.
      const Eigen::Vector2d db(eb[0], eb[1]), da(-ea[0], -ea[1]);
      const bool toward_b = sigma0 > 0 || (sigma0 == 0 && g.dot(db) < 0);
      const Eigen::Vector2d d = toward_b ? db : da;
      const double gd = g.dot(d), hd = d.dot(h * d);
      const double s = hd > 0 ? -gd / hd : -gd / (h.norm() + 1e-300);
      if (sigma0 == 0 && (toward_b ? !(s > 0) : !(s < 0))) return;
      sigma1 = sigma0 + s;
      if ((sigma0 > 0 && sigma1 < 0) || (sigma0 < 0 && sigma1 > 0)) sigma1 = 0;  // stop at the kink
      sigma1 = std::clamp(sigma1, -std::min(0.45 * la, lim), std::min(0.45 * lb, lim));
      if (!(std::abs(sigma1 - sigma0) > 1e-10 * lim)) return;
    }
    const auto position = [&](double t, double* qx, double* qy) {
      if (kind == RezonePointKind::interior) {
        *qx = px + t * sx;
        *qy = py + t * sy;
      } else {
        const double sg = sigma0 + t * (sigma1 - sigma0);
        if (sg >= 0) {
          *qx = x_lag[p] + sg * eb[0];
          *qy = y_lag[p] + sg * eb[1];
        } else {
          *qx = x_lag[p] - sg * ea[0];
          *qy = y_lag[p] - sg * ea[1];
        }
      }
    };
    // Backtracking: accept the first fraction that lowers F and keeps every zone around p
    // as valid as it was.
    for (double t = 1; t > 0.1; t *= 0.5) {
      double qx, qy;
      position(t, &qx, &qy);
      if (!(local_value(lp, p, qx, qy, xs, ys, delta, w, tau) < f0)) continue;
      bool ok = true;
      for (Index i = cb; i < ce && ok; ++i) {
        const Index z = mesh.corner_zone[mesh.point_corners[i]];
        if (zone_crosses(zone_vertices(mesh, z, xs, ys, p, qx, qy)) && !zone_crosses(zone_vertices(mesh, z, xs, ys)))
          ok = false;
      }
      if (!ok) continue;
      xs[p] = qx;
      ys[p] = qy;
      if (kind == RezonePointKind::slide) ws.arc[p] = sigma0 + t * (sigma1 - sigma0);
      break;
    }
  };
  for (int sweep = 0; sweep < options.iterations; ++sweep)
    for (std::size_t colour = 0; colour + 1 < rc.colour_begin.size(); ++colour) {
      const Index cb = rc.colour_begin[colour], count = rc.colour_begin[colour + 1] - cb;
#pragma omp parallel for schedule(static) if (count > 20000)
      for (Index i = 0; i < count; ++i) update(rc.colour_points[cb + i]);
    }

  return relax_and_guard(mesh, rc, options.relaxation, x_lag, y_lag, ws.xs, ws.ys, x_new, y_new, ws);
}

namespace {
// Whether every median-mesh corner of v surely has a positive area, cheaply: corner k's area
// is (x_{k+1} - x_{k-1}) x (g - x_k) / 4, g the vertex mean. The margin, 1e-12 of the squared
// largest coordinate, is far above the rounding of PlanarGeometry::corner_areas (a shoelace on
// absolute coordinates), so where this says yes, so would corner_areas; otherwise corner_areas
// decides.
bool corners_surely_positive(const ZoneVertices& v) {
  const int n = v.n;
  double gx = 0, gy = 0, big = 0;
  for (int k = 0; k < n; ++k) {
    gx += v.x[k], gy += v.y[k];
    big = std::max({big, std::abs(v.x[k]), std::abs(v.y[k])});
  }
  gx /= n, gy /= n;
  const double margin = 1e-12 * big * big;
  for (int k = 0; k < n; ++k) {
    const int kp = k + 1 == n ? 0 : k + 1, km = k == 0 ? n - 1 : k - 1;
    if (!((v.x[kp] - v.x[km]) * (gy - v.y[k]) - (v.y[kp] - v.y[km]) * (gx - v.x[k]) > margin)) return false;
  }
  return true;
}
}  // namespace

RezoneResult relax_and_guard(const Mesh& mesh, const RezoneConstraints& rc, double relaxation,
                             std::span<const double> x_lag, std::span<const double> y_lag,
                             std::span<const double> x_smooth, std::span<const double> y_smooth,
                             std::span<double> x_new, std::span<double> y_new, RezoneWorkspace& ws) {
  const Index np = mesh.num_points(), nz = mesh.num_zones();
  if (!(relaxation >= 0 && relaxation <= 1))
    throw Error("rezone: relaxation = " + std::to_string(relaxation) + " is outside [0, 1]");
  for (const auto& [span, name] : {std::pair{x_lag, "x_lag"}, std::pair{y_lag, "y_lag"},
                                   std::pair{x_smooth, "x_smooth"}, std::pair{y_smooth, "y_smooth"}})
    check_size(span, np, name, mesh);
  check_size({x_new.data(), x_new.size()}, np, "x_new", mesh);
  check_size({y_new.data(), y_new.size()}, np, "y_new", mesh);
  if (static_cast<Index>(rc.kind.size()) != np)
    throw Error("rezone: the constraints were built for " + std::to_string(rc.kind.size()) + " points, the mesh " +
                mesh.source + " has " + std::to_string(np));
  RezoneResult result;
  const double* xs = x_smooth.data();
  const double* ys = y_smooth.data();
  const RezoneOptions options{.relaxation = relaxation};
  // Relaxation toward the Lagrangian mesh, then the validity guard: a zone valid at the
  // Lagrangian positions that is not valid now halves the weight of its points; after a few
  // rounds its points go back to the Lagrangian positions, where it is valid.
  const auto blend = [&](Index p, double w) {
    if (rc.kind[p] == RezonePointKind::fixed || w == 0) {
      x_new[p] = x_lag[p];
      y_new[p] = y_lag[p];
    } else {
      x_new[p] = x_lag[p] + w * (xs[p] - x_lag[p]);
      y_new[p] = y_lag[p] + w * (ys[p] - y_lag[p]);
    }
  };
#pragma omp parallel for schedule(static) if (np > 20000)
  for (Index p = 0; p < np; ++p) blend(p, options.relaxation);
  std::vector<std::uint8_t>& bad_zone = ws.flag;
  bad_zone.resize(nz);
  for (int round = 0;; ++round) {
    Index bad = 0;
#pragma omp parallel for schedule(static) reduction(+ : bad) if (nz > 20000)
    for (Index z = 0; z < nz; ++z) {
      const ZoneVertices v = zone_vertices(mesh, z, x_new.data(), y_new.data());
      // A valid zone can still have a median-mesh corner of non-positive area (a dart whose
      // vertex mean lies past its reflex vertex): the hydro calls that tangled (docs/algorithm.md
      // §9), and the remap cannot give such a corner (its subcell) a mass.
      double corner[kMaxZoneVertices];
      if (zone_crosses(v))
        bad_zone[z] = !zone_crosses(zone_vertices(mesh, z, x_lag.data(), y_lag.data()));
      else
        bad_zone[z] = !corners_surely_positive(v) && !(PlanarGeometry::corner_areas(v, corner) > 0) &&
                      PlanarGeometry::corner_areas(zone_vertices(mesh, z, x_lag.data(), y_lag.data()), corner) > 0;
      bad += bad_zone[z];
    }
    if (bad == 0) break;
    if (round == 0) ws.weight.assign(np, options.relaxation);
    result.backoff_rounds = round + 1;
    for (Index z = 0; z < nz; ++z) {
      if (!bad_zone[z]) continue;
      for (Index c = mesh.zone_corner_begin[z]; c < mesh.zone_corner_begin[z + 1]; ++c) {
        const Index p = mesh.corner_point[c];
        if (ws.weight[p] == options.relaxation) ++result.backed_off_points;
        // Halve once per round, however many bad zones share the point (-0: marked).
        if (!std::signbit(ws.weight[p])) ws.weight[p] = round >= 8 ? -0.0 : -0.5 * ws.weight[p];
      }
    }
    for (Index p = 0; p < np; ++p)
      if (std::signbit(ws.weight[p])) {
        ws.weight[p] = -ws.weight[p];
        blend(p, ws.weight[p]);
      }
  }
  double largest2 = 0;
#pragma omp parallel for schedule(static) reduction(max : largest2) if (np > 20000)
  for (Index p = 0; p < np; ++p) {
    const double dx = x_new[p] - x_lag[p], dy = y_new[p] - y_lag[p];
    largest2 = std::max(largest2, dx * dx + dy * dy);
  }
  result.max_displacement = std::sqrt(largest2);
  return result;
}

namespace {
// Quality of one zone: min over its corners.
double zone_quality_impl(const Mesh& mesh, Index z, QualityMeasure measure, const double* x, const double* y,
                         const double* xr, const double* yr) {
  const Index b = mesh.zone_corner_begin[z], e = mesh.zone_corner_begin[z + 1];
  const int m = static_cast<int>(e - b);
  double q = std::numeric_limits<double>::infinity();
  for (Index c = b; c < e; ++c) {
    const Index p0 = mesh.corner_point[c], p1 = mesh.corner_point[c + 1 == e ? b : c + 1],
                p2 = mesh.corner_point[c == b ? e - 1 : c - 1];
    const double ux = x[p1] - x[p0], uy = y[p1] - y[p0], vx = x[p2] - x[p0], vy = y[p2] - y[p0];
    double value;
    if (measure == QualityMeasure::scaled_jacobian) {
      const double lu = norm2(ux, uy), lv = norm2(vx, vy);
      value = lu > 0 && lv > 0 ? (ux * vy - uy * vx) / (lu * lv) : 0.0;
    } else {
      const CornerTarget t = reference_target(xr[p1] - xr[p0], yr[p1] - yr[p0], xr[p2] - xr[p0], yr[p2] - yr[p0], m);
      const CornerValue v = corner_value(t, ux, uy, vx, vy);
      value = v.n > 0 ? 2 * v.d / v.n : 0.0;
    }
    q = std::min(q, value);
  }
  return q;
}
}  // namespace

double zone_quality(const Mesh& mesh, Index z, QualityMeasure measure, std::span<const double> x,
                    std::span<const double> y, std::span<const double> x_ref, std::span<const double> y_ref) {
  if (z < 0 || z >= mesh.num_zones())
    throw Error("zone_quality: zone " + std::to_string(z) + " is not in the mesh " + mesh.source);
  check_size(x, mesh.num_points(), "x", mesh);
  check_size(y, mesh.num_points(), "y", mesh);
  if (measure == QualityMeasure::reference_shape) {
    check_size(x_ref, mesh.num_points(), "x_ref", mesh);
    check_size(y_ref, mesh.num_points(), "y_ref", mesh);
  }
  return zone_quality_impl(mesh, z, measure, x.data(), y.data(), x_ref.data(), y_ref.data());
}

QualitySummary mesh_quality_summary(const Mesh& mesh, QualityMeasure measure, std::span<const double> x,
                                    std::span<const double> y, std::span<const double> x_ref,
                                    std::span<const double> y_ref) {
  check_size(x, mesh.num_points(), "x", mesh);
  check_size(y, mesh.num_points(), "y", mesh);
  if (measure == QualityMeasure::reference_shape) {
    check_size(x_ref, mesh.num_points(), "x_ref", mesh);
    check_size(y_ref, mesh.num_points(), "y_ref", mesh);
  }
  QualitySummary s;
  const Index nz = mesh.num_zones();
  if (nz == 0) return s;
  double sum = 0;
  s.worst = std::numeric_limits<double>::infinity();
  for (Index z = 0; z < nz; ++z) {
    const double q = zone_quality_impl(mesh, z, measure, x.data(), y.data(), x_ref.data(), y_ref.data());
    sum += q;
    if (q < s.worst) {
      s.worst = q;
      s.worst_zone = z;
    }
  }
  s.mean = sum / nz;
  return s;
}

}  // namespace stagger
