// Plate with three circular holes: a domain that only an unstructured mesher can fill.
// Frontal-Delaunay triangles recombined into quads (blossom); leftover triangles follow
// the caller's triangle policy. Mesh size lc.
DefineConstant[ width = 2, height = 1, lc = 0.05 ];

// The plate.
Point(1) = {0, 0, 0, lc};
Point(2) = {width, 0, 0, lc};
Point(3) = {width, height, 0, lc};
Point(4) = {0, height, 0, lc};
Line(1) = {1, 2};  Line(2) = {2, 3};  Line(3) = {3, 4};  Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};

// Three holes: centres (hx, hy) and radii hr; each is four quarter arcs (gmsh's Circle
// needs arcs below pi). Point tags from 10, curve tags from 10, loop tags from 2.
hx[] = {0.5, 1.2, 1.55};
hy[] = {0.5, 0.3, 0.7};
hr[] = {0.2, 0.12, 0.15};
hole_curves[] = {};
hole_loops[] = {};
For k In {0 : 2}
  c = 10 + 5 * k;
  Point(c) = {hx[k], hy[k], 0, lc};
  Point(c + 1) = {hx[k] + hr[k], hy[k], 0, lc};
  Point(c + 2) = {hx[k], hy[k] + hr[k], 0, lc};
  Point(c + 3) = {hx[k] - hr[k], hy[k], 0, lc};
  Point(c + 4) = {hx[k], hy[k] - hr[k], 0, lc};
  a = 10 + 4 * k;
  Circle(a) = {c + 1, c, c + 2};
  Circle(a + 1) = {c + 2, c, c + 3};
  Circle(a + 2) = {c + 3, c, c + 4};
  Circle(a + 3) = {c + 4, c, c + 1};
  Curve Loop(2 + k) = {a, a + 1, a + 2, a + 3};
  hole_curves[] += {a, a + 1, a + 2, a + 3};
  hole_loops[] += {2 + k};
EndFor

Plane Surface(1) = {1, hole_loops[]};

Mesh.Algorithm = 6;            // Frontal-Delaunay (8, the quad variant, crashes in gmsh 4.8 on Debian)
Mesh.RecombinationAlgorithm = 1;  // blossom
Recombine Surface{1};

Physical Surface("plate") = {1};
Physical Curve("outer") = {1, 2, 3, 4};
Physical Curve("holes") = {hole_curves[]};
