// The plane-strain Taylor bar: a 1 x 5 cm copper bar standing on the rigid wall y = 0
// (SI units, m), meshed unstructured: Frontal-Delaunay triangles recombined into quads
// (blossom), about n zones across the width (mesh size width / n).
DefineConstant[ width = 0.01, length = 0.05, n = 20 ];
lc = width / n;

Point(1) = {-width / 2, 0, 0, lc};
Point(2) = {width / 2, 0, 0, lc};
Point(3) = {width / 2, length, 0, lc};
Point(4) = {-width / 2, length, 0, lc};
Line(1) = {1, 2};  Line(2) = {2, 3};  Line(3) = {3, 4};  Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

Mesh.Algorithm = 6;               // Frontal-Delaunay
Mesh.RecombinationAlgorithm = 1;  // blossom
Recombine Surface{1};

Physical Surface("bar") = {1};
Physical Curve("impact") = {1};   // on the wall
Physical Curve("sides") = {2, 4};
Physical Curve("top") = {3};
