// Volume fractions of fill shapes (fill_fractions.hpp).
#include "mixed/fill_fractions.hpp"

#include <algorithm>
#include <cmath>

namespace stagger::mixed {

namespace {

double cross(const Point& a, const Point& b) {
  return a[0] * b[1] - a[1] * b[0];
}
double dot(const Point& a, const Point& b) {
  return a[0] * b[0] + a[1] * b[1];
}
Point minus(const Point& a, const Point& b) {
  return {a[0] - b[0], a[1] - b[1]};
}
Point lerp(const Point& a, const Point& b, double t) {
  return {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])};
}

// Keeps the part of `polygon` on the left of the directed line p -> q (Sutherland-Hodgman).
Polygon clip_left_of(const Polygon& polygon, const Point& p, const Point& q) {
  Polygon out;
  const Point d = minus(q, p);
  const std::size_t n = polygon.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Point& a = polygon[k];
    const Point& b = polygon[(k + 1) % n];
    const double sa = cross(d, minus(a, p)), sb = cross(d, minus(b, p));
    if (sa >= 0) out.push_back(a);
    if ((sa >= 0) != (sb >= 0)) out.push_back(lerp(a, b, sa / (sa - sb)));
  }
  return out;
}

// Signed area of the disc (centred at the origin, radius r) inside the triangle (0, a, b).
double disc_in_origin_triangle(const Point& a, const Point& b, double r) {
  const Point d = minus(b, a);
  // |a + t d|^2 = r^2: t^2 |d|^2 + 2 t a.d + |a|^2 - r^2 = 0
  const double qa = dot(d, d), qb = dot(a, d), qc = dot(a, a) - r * r;
  double cuts[4] = {0, 0, 0, 1};
  int count = 1;
  const double disc = qb * qb - qa * qc;
  if (qa > 0 && disc > 0) {
    const double root = std::sqrt(disc);
    for (const double t : {(-qb - root) / qa, (-qb + root) / qa})
      if (t > 0 && t < 1) cuts[count++] = t;
  }
  cuts[count++] = 1;
  double area = 0;
  for (int k = 0; k + 1 < count; ++k) {
    const Point p = lerp(a, b, cuts[k]), q = lerp(a, b, cuts[k + 1]);
    const Point mid = lerp(a, b, 0.5 * (cuts[k] + cuts[k + 1]));
    if (dot(mid, mid) <= r * r)
      area += 0.5 * cross(p, q);  // the piece of the edge is inside: a triangle
    else
      area += 0.5 * r * r * std::atan2(cross(p, q), dot(p, q));  // outside: a sector
  }
  return area;
}

// Area where the linear interpolant of the corner values (la, lb, lc) is positive.
double linear_positive_area(const Point& a, const Point& b, const Point& c, double la, double lb, double lc) {
  Polygon triangle{a, b, c};
  const double whole = std::abs(signed_area(triangle));
  const double values[3] = {la, lb, lc};
  Polygon positive;
  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3;
    if (values[k] > 0) positive.push_back(triangle[k]);
    if ((values[k] > 0) != (values[k1] > 0))
      positive.push_back(lerp(triangle[k], triangle[k1], values[k] / (values[k] - values[k1])));
  }
  return positive.size() < 3 ? 0.0 : std::min(whole, std::abs(signed_area(positive)));
}

struct LevelIntegrator {
  const std::function<double(double, double)>& level;
  int max_depth;
  double error = 0;

  // Area of {level > 0} in the triangle with corner values la, lb, lc.
  double area(const Point& a, const Point& b, const Point& c, double la, double lb, double lc, int depth) {
    const double whole = 0.5 * std::abs(cross(minus(b, a), minus(c, a)));
    const Point ab = lerp(a, b, 0.5), bc = lerp(b, c, 0.5), ca = lerp(c, a, 0.5);
    const double lab = level(ab[0], ab[1]), lbc = level(bc[0], bc[1]), lca = level(ca[0], ca[1]);
    const bool all_in = la > 0 && lb > 0 && lc > 0 && lab > 0 && lbc > 0 && lca > 0;
    const bool all_out = !(la > 0) && !(lb > 0) && !(lc > 0) && !(lab > 0) && !(lbc > 0) && !(lca > 0);
    if (depth >= 2 && (all_in || all_out)) return all_in ? whole : 0.0;
    if (depth >= max_depth) {
      // A cut leaf: the linear estimate on the four children, and its change against the parent's.
      const double fine =
          linear_positive_area(a, ab, ca, la, lab, lca) + linear_positive_area(ab, b, bc, lab, lb, lbc) +
          linear_positive_area(ca, bc, c, lca, lbc, lc) + linear_positive_area(ab, bc, ca, lab, lbc, lca);
      error += std::abs(fine - linear_positive_area(a, b, c, la, lb, lc));
      return fine;
    }
    return area(a, ab, ca, la, lab, lca, depth + 1) + area(ab, b, bc, lab, lb, lbc, depth + 1) +
           area(ca, bc, c, lca, lbc, lc, depth + 1) + area(ab, bc, ca, lab, lbc, lca, depth + 1);
  }
};

}  // namespace

double signed_area(const Polygon& polygon) {
  double twice = 0;
  const std::size_t n = polygon.size();
  for (std::size_t k = 0; k < n; ++k) twice += cross(polygon[k], polygon[(k + 1) % n]);
  return 0.5 * twice;
}

double area_inside_triangle(const Polygon& subject, const Point& a, const Point& b, const Point& c) {
  const bool ccw = cross(minus(b, a), minus(c, a)) > 0;
  Polygon clipped = subject;
  const Point corners[3] = {a, ccw ? b : c, ccw ? c : b};
  for (int k = 0; k < 3 && clipped.size() >= 3; ++k) clipped = clip_left_of(clipped, corners[k], corners[(k + 1) % 3]);
  return clipped.size() < 3 ? 0.0 : std::abs(signed_area(clipped));
}

double intersection_area(const Polygon& zone, const Polygon& shape) {
  double area = 0;
  for (std::size_t k = 1; k + 1 < zone.size(); ++k) {
    const double fan = cross(minus(zone[k], zone[0]), minus(zone[k + 1], zone[0]));
    if (fan == 0) continue;
    area += (fan > 0 ? 1.0 : -1.0) * area_inside_triangle(shape, zone[0], zone[k], zone[k + 1]);
  }
  return std::abs(area);
}

double disc_intersection_area(const Polygon& zone, const Point& centre, double r) {
  double area = 0;
  const std::size_t n = zone.size();
  for (std::size_t k = 0; k < n; ++k)
    area += disc_in_origin_triangle(minus(zone[k], centre), minus(zone[(k + 1) % n], centre), r);
  return std::abs(area);
}

double level_set_area(const Polygon& zone, const std::function<double(double, double)>& level, int max_depth,
                      double* error_bound) {
  LevelIntegrator integrator{level, max_depth};
  const double l0 = level(zone[0][0], zone[0][1]);
  double area = 0;
  for (std::size_t k = 1; k + 1 < zone.size(); ++k) {
    const double fan = cross(minus(zone[k], zone[0]), minus(zone[k + 1], zone[0]));
    if (fan == 0) continue;
    const double part = integrator.area(zone[0], zone[k], zone[k + 1], l0, level(zone[k][0], zone[k][1]),
                                        level(zone[k + 1][0], zone[k + 1][1]), 0);
    area += (fan > 0 ? 1.0 : -1.0) * part;
  }
  if (error_bound != nullptr) *error_bound = integrator.error;
  return std::abs(area);
}

}  // namespace stagger::mixed
