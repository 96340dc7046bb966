// The walled 2 x 1 box of the blast scenes, meshed unstructured: Frontal-Delaunay triangles
// recombined into quads (blossom), about n zones across the height (mesh size 1/n).
DefineConstant[ width = 2, height = 1, n = 50 ];
lc = height / n;

Point(1) = {0, 0, 0, lc};
Point(2) = {width, 0, 0, lc};
Point(3) = {width, height, 0, lc};
Point(4) = {0, height, 0, lc};
Line(1) = {1, 2};  Line(2) = {2, 3};  Line(3) = {3, 4};  Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

Mesh.Algorithm = 6;               // Frontal-Delaunay
Mesh.RecombinationAlgorithm = 1;  // blossom
Recombine Surface{1};

Physical Surface("domain") = {1};
Physical Curve("left") = {4};
Physical Curve("right") = {2};
Physical Curve("bottom") = {1};
Physical Curve("top") = {3};
