// A triangle whose boundary has an odd number of mesh edges (3 sides x 5 segments = 15).
// A mesh made only of quads always has an even number of boundary edges, so recombination
// must leave at least one triangle here: the test geometry for the triangle policy
// (accept: mixed zones; subdivide: all quads; reject: error).
DefineConstant[ n = 5 ];

Point(1) = {0, 0, 0};
Point(2) = {1, 0, 0};
Point(3) = {0, 1, 0};
Line(1) = {1, 2};   // bottom
Line(2) = {2, 3};   // hypotenuse
Line(3) = {3, 1};   // left
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};
Transfinite Curve{1:3} = n + 1;   // n segments per side, 3n boundary edges
Mesh.Algorithm = 6;
Recombine Surface{1};

Physical Surface("triangle") = {1};
Physical Curve("bottom") = {1};
Physical Curve("hypotenuse") = {2};
Physical Curve("left") = {3};
