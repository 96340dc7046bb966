#pragma once
// Volume fractions of a fill shape in one zone (docs/scenes.md, "[[fill]]"): the area of the
// zone polygon that lies inside a polygon, a circle or an expression, divided by the zone area.
// Polygons and circles are exact up to round-off (clipping; the circle's area of intersection
// with each signed triangle of the zone's fan); expressions are sub-sampled adaptively.
#include <array>
#include <functional>
#include <vector>

namespace stagger::mixed {

using Point = std::array<double, 2>;
using Polygon = std::vector<Point>;  // counter-clockwise or clockwise, simple

// Signed area (shoelace), positive for counter-clockwise.
double signed_area(const Polygon& polygon);

// Area of polygon `subject` (any simple polygon) inside the triangle (a, b, c) of either
// orientation: Sutherland-Hodgman clipping against the triangle's three half-planes.
double area_inside_triangle(const Polygon& subject, const Point& a, const Point& b, const Point& c);

// Area of the intersection of two simple polygons: the zone is split into the signed triangles
// of its fan from vertex 0, whose signed indicators sum to the zone's (a.e.), and the shape is
// clipped against each. Neither polygon needs to be convex.
double intersection_area(const Polygon& zone, const Polygon& shape);

// Area of the intersection of a simple polygon with the disc of centre `centre` and radius r:
// the sum over the polygon's edges (a, b) of the signed area of the disc inside the triangle
// (centre, a, b), each piece a triangle or a circular sector in closed form.
double disc_intersection_area(const Polygon& zone, const Point& centre, double r);

// Area of the zone where `level(x, y) > 0` (a level set; for a comparison "lhs < rhs" the
// scene passes rhs - lhs). Adaptive: the zone's fan triangles are split into four similar
// triangles (two levels always, to see features larger than a quarter of the zone); deeper, a
// triangle is split only while the signs at its corners and edge midpoints differ, down to
// `max_depth`. In a cut leaf the part where the linear interpolant of the values is positive
// is integrated exactly, so a straight zero line is exact and a curved one of curvature kappa
// errs by the segment between the curve and its chord, about kappa h^2 l / 12 for a chord of
// length l in a leaf of size h: summed, kappa L h^2 / 12 for a zero line of length L in the
// zone. `error_bound` (if not null) receives the a-posteriori estimate docs/scenes.md quotes:
// the sum over cut leaves of the change between the leaf's linear estimate and that of its
// four children.
double level_set_area(const Polygon& zone, const std::function<double(double, double)>& level, int max_depth,
                      double* error_bound = nullptr);

}  // namespace stagger::mixed
