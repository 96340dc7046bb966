// Quarter of a shell: the annulus ri <= r <= ro, 0 <= theta <= pi/2, meshed transfinite
// with equal angles (n_theta zones around) and equal radial steps (n_r zones across).
// Override any parameter by name, e.g. stagger mesh quarter_shell.geo --set n_theta=40.
//
// Why every arc node is an explicit point: a transfinite Circle spaces its nodes by a
// numerically integrated arc length, which gmsh 4.8 gets equal only to ~6e-10 rad (measured
// on 20x16); the Be shell then loses its symmetry at 1e-10 instead of round-off. Here node k
// of an arc is the point (r cos(k h), r sin(k h)), h = (pi/2) / n_theta, computed once, and
// the nodes past the diagonal are the mirror images (y, x) of those before it, so the mesh
// is equal-angle and mirror-symmetric about the diagonal to round-off. Each arc is a chain
// of n_theta one-zone Circle segments, and the transfinite (Coons) interpolation between
// them puts every interior node on its circle and its ray (docs/solids.md).
DefineConstant[ ri = 0.08, ro = 0.1, n_theta = 20, n_r = 16 ];

h = Pi / 2 / n_theta;
Point(1) = {0, 0, 0};  // centre of the arcs (not meshed)

// Arc nodes: inner k -> point 10 + k, outer k -> point 10 + n_theta + 1 + k.
For k In {0 : n_theta}
  If (2 * k <= n_theta)
    c = Cos(k * h);
    s = Sin(k * h);
  Else
    c = Sin((n_theta - k) * h);
    s = Cos((n_theta - k) * h);
  EndIf
  Point(10 + k) = {ri * c, ri * s, 0};
  Point(11 + n_theta + k) = {ro * c, ro * s, 0};
EndFor
inner0 = 10;
outer0 = 11 + n_theta;

// The straight sides are chains of n_r one-zone lines between explicit points too (gmsh
// also spaces a transfinite Line by integrated length: 2e-14 off, measured), at the radii
// ri + (ro - ri) j / n_r of meshgen::annulus_sector.
// Start side (y = 0) points: sb + j; end side (x = 0): eb + j, j = 1 .. n_r - 1. The same
// numbers serve the side lines. The bases grow with n_theta and n_r so that no id is used
// twice at any resolution (a redefined entity crashes gmsh 4.8 with a double free).
sb = 20 + 2 * n_theta;
eb = sb + n_r + 1;
start_lines[] = {};
end_lines[] = {};
For j In {1 : n_r - 1}
  Point(sb + j) = {ri + (ro - ri) * j / n_r, 0, 0};
  Point(eb + j) = {0, ri + (ro - ri) * j / n_r, 0};
EndFor
For j In {0 : n_r - 1}
  a = sb + j;
  b = sb + j + 1;
  If (j == 0)
    a = inner0;
  EndIf
  If (j == n_r - 1)
    b = outer0;
  EndIf
  Line(sb + j) = {a, b};  // start side, outward
  start_lines[] += {sb + j};
  a = eb + n_r - j;
  b = eb + n_r - j - 1;
  If (j == 0)
    a = outer0 + n_theta;
  EndIf
  If (j == n_r - 1)
    b = inner0 + n_theta;
  EndIf
  Line(eb + j) = {a, b};  // end side, inward
  end_lines[] += {eb + j};
EndFor
// Outer arc counter-clockwise (curves 10 ..), inner arc clockwise (curves 10 + n_theta ..).
outer_arcs[] = {};
inner_arcs[] = {};
For k In {0 : n_theta - 1}
  Circle(10 + k) = {outer0 + k, 1, outer0 + k + 1};
  outer_arcs[] += {10 + k};
  Circle(10 + n_theta + k) = {inner0 + n_theta - k, 1, inner0 + n_theta - k - 1};
  inner_arcs[] += {10 + n_theta + k};
EndFor

Curve Loop(1) = {start_lines[], outer_arcs[], end_lines[], inner_arcs[]};  // counter-clockwise
Plane Surface(1) = {1};

// One zone per segment: its two end points.
Transfinite Curve{outer_arcs[], inner_arcs[], start_lines[], end_lines[]} = 2;
Transfinite Surface{1} = {inner0, outer0, outer0 + n_theta, inner0 + n_theta};
Recombine Surface{1};

Physical Surface("shell") = {1};
Physical Curve("inner") = {inner_arcs[]};
Physical Curve("outer") = {outer_arcs[]};
Physical Curve("start") = {start_lines[]};
Physical Curve("end") = {end_lines[]};
