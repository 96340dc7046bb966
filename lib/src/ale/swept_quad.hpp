#pragma once
// The signed swept region of the remap (docs/ale.md, "Remap"): area and first moments of a
// quadrilateral, planar or per radian in rz. Shared by the reconstruction's old geometry, the
// face fluxes and the corner-mass repair.

namespace stagger {

// Signed area and first moments about (ox, oy) of the quadrilateral p0 p1 p2 p3 (any shape,
// self-intersecting included: the signed integral). Coordinates relative to p0 keep the
// cancellation small; an unmoved face gives exactly zero.
struct Swept {
  double area = 0, mx = 0, my = 0;  // area, integral of (x - ox), of (y - oy)
  bool simple = true;               // not a bow-tie (one diagonal splits it into like-signed triangles)
};

// rz: the same with the measure r dA (x = r): area -> V = int x dA, mx -> int (x - ox) x dA,
// my -> int (y - oy) x dA, from the second moments of the signed quadrilateral.
template <bool Rz = false>
inline Swept swept_quad(double x0, double y0, double x1, double y1, double x2, double y2, double x3, double y3,
                        double ox, double oy) {
  const double ax[4] = {0.0, x1 - x0, x2 - x0, x3 - x0};
  const double ay[4] = {0.0, y1 - y0, y2 - y0, y3 - y0};
  double a2 = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int i = 1; i < 3; ++i) {  // the terms with the origin vanish
    const double cr = ax[i] * ay[i + 1] - ax[i + 1] * ay[i];
    a2 += cr;
    sx += (ax[i] + ax[i + 1]) * cr;
    sy += (ay[i] + ay[i + 1]) * cr;
    if constexpr (Rz) {
      sxx += (ax[i] * ax[i] + ax[i] * ax[i + 1] + ax[i + 1] * ax[i + 1]) * cr;
      sxy += (ax[i] * ay[i + 1] + 2 * ax[i] * ay[i] + 2 * ax[i + 1] * ay[i + 1] + ax[i + 1] * ay[i]) * cr;
    }
  }
  Swept s;
  s.area = 0.5 * a2;
  // Triangles of the two diagonal splits: (0,1,2) + (0,2,3) and (1,2,3) + (1,3,0).
  const double t012 = ax[1] * ay[2] - ax[2] * ay[1], t023 = ax[2] * ay[3] - ax[3] * ay[2];
  const double t123 = (ax[2] - ax[1]) * (ay[3] - ay[1]) - (ax[3] - ax[1]) * (ay[2] - ay[1]);
  const double t130 = (ax[3] - ax[1]) * (0 - ay[1]) - (0 - ax[1]) * (ay[3] - ay[1]);
  s.simple = t012 * t023 >= 0 || t123 * t130 >= 0;
  if constexpr (Rz) {
    // Relative to p0: A, int x', int y', int x'^2, int x'y'; then x = x' + x0, y = y' + y0.
    const double area = s.area, ix = sx / 6.0, iy = sy / 6.0, ixx = sxx / 12.0, ixy = sxy / 24.0;
    s.area = ix + x0 * area;
    s.mx = ixx + 2 * x0 * ix + x0 * x0 * area - ox * s.area;
    s.my = ixy + x0 * iy + y0 * ix + x0 * y0 * area - oy * s.area;
    return s;
  }
  s.mx = sx / 6.0 + (x0 - ox) * s.area;
  s.my = sy / 6.0 + (y0 - oy) * s.area;
  return s;
}

}  // namespace stagger
