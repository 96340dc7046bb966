// The ALE rezone (docs/ale.md, "Rezone"): point-by-point minimisation of a corner-Jacobian
// smoothness functional, relaxation toward the Lagrangian mesh, and a validity guard.
#include "ale/rezone.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "ale/norm2.hpp"
#include "hydro/kernels/zone_validity.hpp"
#include "stagger/error.hpp"

namespace stagger {
namespace {

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

// The inputs of rezone: options in range, arrays of the mesh's sizes, outputs that are not the
// inputs, constraints built for this mesh.
void check_rezone_inputs(const Mesh& mesh, const RezoneConstraints& rc, const RezoneOptions& options,
                         std::span<const double> x_lag, std::span<const double> y_lag, std::span<const double> x_ref,
                         std::span<const double> y_ref, std::span<double> x_new, std::span<double> y_new) {
  check_options(options);
  const Index np = mesh.num_points();
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
  if (options.method == RezoneMethod::reference_jacobian) {
    check_size(x_ref, np, "x_ref", mesh);
    check_size(y_ref, np, "y_ref", mesh);
  }
}

// The reference-Jacobian functional's corner targets, 4 per corner (k11, k12, k22, det_m), from
// the reference mesh (constant, but recomputing keeps the call pure; O(corners)).
void reference_corner_targets(const Mesh& mesh, std::span<const double> x_ref, std::span<const double> y_ref,
                              std::vector<double>& target) {
  const Index nz = mesh.num_zones();
  target.resize(4 * static_cast<std::size_t>(mesh.num_corners()));
  for (Index z = 0; z < nz; ++z) {
    const Index b = mesh.zone_corner_begin[z], e = mesh.zone_corner_begin[z + 1];
    const int m = static_cast<int>(e - b);
    for (Index c = b; c < e; ++c) {
      const Index p0 = mesh.corner_point[c], p1 = mesh.corner_point[c + 1 == e ? b : c + 1],
                  p2 = mesh.corner_point[c == b ? e - 1 : c - 1];
      const CornerTarget t = reference_target(x_ref[p1] - x_ref[p0], y_ref[p1] - y_ref[p0], x_ref[p2] - x_ref[p0],
                                              y_ref[p2] - y_ref[p0], m);
      target[4 * c] = t.k11;
      target[4 * c + 1] = t.k12;
      target[4 * c + 2] = t.k22;
      target[4 * c + 3] = t.det_m;
    }
  }
}

// Each point moves at most max_move times its shortest Lagrangian edge (a gather over the
// point's corners, so the loop is parallel). The bound is on the final, relaxed move: the
// smoothed move may be 1 / relaxation times longer (up to one edge). Capping the smoothed
// move instead leaves relaxation * max_move of an edge per remap, and where the flow closes
// an edge (a shock reflecting off a wall) the rezone then cannot reopen it as fast as the
// flow shuts it: the cap shrinks with the edge and the zone collapses (docs/ale.md).
void move_limits(const Mesh& mesh, const RezoneConstraints& rc, const RezoneOptions& options,
                 std::span<const double> x_lag, std::span<const double> y_lag, std::vector<double>& move_limit) {
  const Index np = mesh.num_points();
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
    move_limit[p] = limit_factor * std::sqrt(shortest2);
  }
}

// A slide point's two boundary edges at the Lagrangian positions: the directions e_a, e_b
// toward its boundary neighbours, and their lengths (which bound the slide).
struct SlideEdges {
  double ea[2] = {0, 0}, eb[2] = {0, 0}, la = 0, lb = 0;
};

// Slide point p's edges; false where it does not slide this call: an edge of zero length, or
// a boundary that turns by more than the corner angle (cos_corner its cosine).
bool slide_edges(const RezoneConstraints& rc, Index p, std::span<const double> x_lag, std::span<const double> y_lag,
                 double cos_corner, SlideEdges& s) {
  const auto [a, b] = rc.boundary_neighbours[p];
  const double ax = x_lag[a] - x_lag[p], ay = y_lag[a] - y_lag[p];
  const double bx = x_lag[b] - x_lag[p], by = y_lag[b] - y_lag[p];
  s.la = norm2(ax, ay);
  s.lb = norm2(bx, by);
  if (!(s.la > 0 && s.lb > 0)) return false;
  s.ea[0] = ax / s.la, s.ea[1] = ay / s.la, s.eb[0] = bx / s.lb, s.eb[1] = by / s.lb;
  return -(s.ea[0] * s.eb[0] + s.ea[1] * s.eb[1]) >= cos_corner;
}

// The corners whose Jacobian depends on point p (in each zone, the corner at p and its two
// neighbours), with their targets, and the smallest, largest |.| and sum of their D at
// (xs, ys). False if there are more than kMaxLocal.
bool local_corners(const Mesh& mesh, Index p, const std::vector<double>& target, const double* xs, const double* ys,
                   LocalProblem& lp, double& dmin, double& dmax, double& dsum) {
  lp.count = 0;
  for (Index i = mesh.point_corner_begin[p]; i < mesh.point_corner_begin[p + 1]; ++i) {
    const Index cp = mesh.point_corners[i], z = mesh.corner_zone[cp];
    const Index b = mesh.zone_corner_begin[z], e = mesh.zone_corner_begin[z + 1];
    const Index prev = cp == b ? e - 1 : cp - 1, next = cp + 1 == e ? b : cp + 1;
    for (const Index c : {prev, cp, next}) {
      if (lp.count == kMaxLocal) return false;
      LocalCorner& l = lp.c[lp.count++];
      l.p0 = mesh.corner_point[c];
      l.p1 = mesh.corner_point[c + 1 == e ? b : c + 1];
      l.p2 = mesh.corner_point[c == b ? e - 1 : c - 1];
      l.target = {target[4 * c], target[4 * c + 1], target[4 * c + 2], target[4 * c + 3]};
      l.alpha = c == cp ? -1.0 : (c == prev ? 1.0 : 0.0);
      l.beta = c == cp ? -1.0 : (c == next ? 1.0 : 0.0);
      const double d =
          corner_value(l.target, xs[l.p1] - xs[l.p0], ys[l.p1] - ys[l.p0], xs[l.p2] - xs[l.p0], ys[l.p2] - ys[l.p0]).d;
      dmin = std::min(dmin, d);
      dmax = std::max(dmax, std::abs(d));
      dsum += d;
    }
  }
  return true;
}

// A candidate move of one point as a function of the step fraction t in (0, 1]: an interior
// point from (px, py) along (sx, sy), a slide point along its old boundary edges from arc
// length sigma0 to sigma1 (>= 0 toward b, < 0 toward a).
struct PointStep {
  RezonePointKind kind;
  double x_lag, y_lag, px, py;
  const SlideEdges* edges;
  double sx = 0, sy = 0;  // interior: full step
  double sigma0 = 0, sigma1 = 0;
  void position(double t, double* qx, double* qy) const {
    if (kind == RezonePointKind::interior) {
      *qx = px + t * sx;
      *qy = py + t * sy;
    } else {
      const double sg = sigma0 + t * (sigma1 - sigma0);
      if (sg >= 0) {
        *qx = x_lag + sg * edges->eb[0];
        *qy = y_lag + sg * edges->eb[1];
      } else {
        *qx = x_lag - sg * edges->ea[0];
        *qy = y_lag - sg * edges->ea[1];
      }
    }
  }
};

// An interior point's Newton step on the local functional (gradient g, Hessian h), with the
// Hessian shifted where it is not safely positive definite, kept within lim of the Lagrangian
// position. False if the step is negligible (the point stays).
bool interior_newton_step(const Eigen::Vector2d& g, const Eigen::Matrix2d& h, double lim, PointStep& st) {
  Eigen::Matrix2d hs = h;
  const double tr = h.trace();
  const double disc = std::sqrt(0.25 * (h(0, 0) - h(1, 1)) * (h(0, 0) - h(1, 1)) + h(0, 1) * h(0, 1));
  const double lmin = 0.5 * tr - disc, lmax = 0.5 * tr + disc;
  if (!(lmin > 1e-8 * std::abs(lmax)))
    hs += (std::abs(lmin) + 1e-3 * std::abs(lmax) + 1e-300) * Eigen::Matrix2d::Identity();
  const Eigen::Vector2d step = hs.llt().solve(-g);
  st.sx = step(0);
  st.sy = step(1);
  // Keep within the move limit around the Lagrangian position.
  const double dx = st.px + st.sx - st.x_lag, dy = st.py + st.sy - st.y_lag;
  const double dist = norm2(dx, dy);
  if (dist > lim) {
    st.sx = st.x_lag + dx * (lim / dist) - st.px;
    st.sy = st.y_lag + dy * (lim / dist) - st.py;
  }
  return norm2(st.sx, st.sy) > 1e-10 * lim;
}

// A slide point's Newton step along the old boundary edge it would run along (sigma0 = its
// current arc length), stopping at the kink and within the edges' and the move limit. False
// if the step is negligible or points off the boundary (the point stays).
bool slide_newton_step(const Eigen::Vector2d& g, const Eigen::Matrix2d& h, double lim, PointStep& st) {
  const SlideEdges& e = *st.edges;
  const double sigma0 = st.sigma0;
  const Eigen::Vector2d db(e.eb[0], e.eb[1]), da(-e.ea[0], -e.ea[1]);
  const bool toward_b = sigma0 > 0 || (sigma0 == 0 && g.dot(db) < 0);
  const Eigen::Vector2d d = toward_b ? db : da;
  const double gd = g.dot(d), hd = d.dot(h * d);
  const double s = hd > 0 ? -gd / hd : -gd / (h.norm() + 1e-300);
  if (sigma0 == 0 && (toward_b ? !(s > 0) : !(s < 0))) return false;
  double sigma1 = sigma0 + s;
  if ((sigma0 > 0 && sigma1 < 0) || (sigma0 < 0 && sigma1 > 0)) sigma1 = 0;  // stop at the kink
  sigma1 = std::clamp(sigma1, -std::min(0.45 * e.la, lim), std::min(0.45 * e.lb, lim));
  st.sigma1 = sigma1;
  return std::abs(sigma1 - sigma0) > 1e-10 * lim;
}

// Backtracking: point p takes the first fraction of the step that lowers the local functional
// below f0 and keeps every zone around p as valid as it was (else it stays).
void backtrack(const Mesh& mesh, Index p, const LocalProblem& lp, const PointStep& st, double f0, double delta,
               double w, double tau, double* xs, double* ys, double& arc) {
  const Index cb = mesh.point_corner_begin[p], ce = mesh.point_corner_begin[p + 1];
  for (double t = 1; t > 0.1; t *= 0.5) {
    double qx, qy;
    st.position(t, &qx, &qy);
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
    if (st.kind == RezonePointKind::slide) arc = st.sigma0 + t * (st.sigma1 - st.sigma0);
    break;
  }
}

// One Gauss-Seidel update of point p by the reference-Jacobian functional (docs/ale.md,
// "Reference-Jacobian smoothing"): a safeguarded Newton step on the functional of the corners
// around p, then backtracking. lim: p's move limit; arc: a slide point's arc length.
void reference_jacobian_point(const Mesh& mesh, Index p, RezonePointKind kind, const SlideEdges& edges,
                              double size_weight, double lim, double x_lag, double y_lag,
                              const std::vector<double>& target, double* xs, double* ys, double& arc) {
  LocalProblem lp;
  double dmin = std::numeric_limits<double>::infinity(), dmax = 0, dsum = 0;
  if (!local_corners(mesh, p, target, xs, ys, lp, dmin, dmax, dsum) || !(dmax > 0)) return;
  // Regularise only where a corner is not convex (then the plain functional has no barrier).
  const double delta = dmin > 0 ? 0.0 : 1e-2 * dmax;
  // Size target: the mean relative corner area around p, frozen for this update (a reference
  // mesh, or any uniform scaling of it, has D = tau everywhere: still a fixed point).
  const double tau = dsum / lp.count;
  const double w = tau > 0 ? size_weight : 0.0;

  Eigen::Vector2d g;
  Eigen::Matrix2d h;
  local_derivatives(lp, xs, ys, delta, w, tau, g, h);
  PointStep st{.kind = kind, .x_lag = x_lag, .y_lag = y_lag, .px = xs[p], .py = ys[p], .edges = &edges};
  st.sigma0 = st.sigma1 = arc;
  const double f0 = local_value(lp, p, st.px, st.py, xs, ys, delta, w, tau);
  if (kind == RezonePointKind::interior ? !interior_newton_step(g, h, lim, st) : !slide_newton_step(g, h, lim, st))
    return;
  backtrack(mesh, p, lp, st, f0, delta, w, tau, xs, ys, arc);
}

// The smoothing: `iterations` Gauss-Seidel sweeps over the free points, from the Lagrangian
// positions to the smoothed ones in (ws.xs, ws.ys). Points of one colour share no zone
// (make_rezone_constraints), so they are independent: a colour is one parallel loop, and the
// result does not depend on the number of threads.
void smoothing_sweeps(const Mesh& mesh, const RezoneConstraints& rc, const RezoneOptions& options,
                      std::span<const double> x_lag, std::span<const double> y_lag, RezoneWorkspace& ws) {
  const bool use_reference = options.method == RezoneMethod::reference_jacobian;
  // Slide points this call: the boundary turns by at most corner_angle at the Lagrangian positions.
  const double cos_corner = std::cos(options.corner_angle_degrees * std::numbers::pi / 180);
  double* xs = ws.xs.data();
  double* ys = ws.ys.data();
  const auto update = [&](Index p) {
    const RezonePointKind kind = rc.kind[p];
    if (kind == RezonePointKind::fixed) return;
    SlideEdges edges;
    if (kind == RezonePointKind::slide && !slide_edges(rc, p, x_lag, y_lag, cos_corner, edges)) return;
    if (use_reference)
      reference_jacobian_point(mesh, p, kind, edges, options.size_weight, ws.move_limit[p], x_lag[p], y_lag[p],
                               ws.target, xs, ys, ws.arc[p]);
    else
      winslow_point(rc, p, kind, edges.ea, edges.eb, edges.la, edges.lb, ws.move_limit[p], x_lag[p], y_lag[p], xs, ys,
                    ws.arc[p]);
  };
  for (int sweep = 0; sweep < options.iterations; ++sweep)
    for (std::size_t colour = 0; colour + 1 < rc.colour_begin.size(); ++colour) {
      const Index cb = rc.colour_begin[colour], count = rc.colour_begin[colour + 1] - cb;
#pragma omp parallel for schedule(static) if (count > 20000)
      for (Index i = 0; i < count; ++i) update(rc.colour_points[cb + i]);
    }
}

}  // namespace

// The stages: inputs checked, the Lagrangian mesh copied (returned as it is for relaxation 0
// or no sweep), the targets and move limits, the smoothing sweeps, then relaxation and guard.
RezoneResult rezone(const Mesh& mesh, const RezoneConstraints& rc, const RezoneOptions& options,
                    std::span<const double> x_lag, std::span<const double> y_lag, std::span<const double> x_ref,
                    std::span<const double> y_ref, std::span<double> x_new, std::span<double> y_new,
                    RezoneWorkspace& ws) {
  check_rezone_inputs(mesh, rc, options, x_lag, y_lag, x_ref, y_ref, x_new, y_new);
  RezoneResult result;
  std::copy(x_lag.begin(), x_lag.end(), x_new.begin());
  std::copy(y_lag.begin(), y_lag.end(), y_new.begin());
  if (options.relaxation == 0 || options.iterations == 0) return result;

  const Index np = mesh.num_points();
  ws.xs.assign(x_lag.begin(), x_lag.end());
  ws.ys.assign(y_lag.begin(), y_lag.end());
  ws.arc.assign(np, 0.0);
  ws.move_limit.resize(np);
  if (options.method == RezoneMethod::reference_jacobian) reference_corner_targets(mesh, x_ref, y_ref, ws.target);
  move_limits(mesh, rc, options, x_lag, y_lag, ws.move_limit);
  smoothing_sweeps(mesh, rc, options, x_lag, y_lag, ws);
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
