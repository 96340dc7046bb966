// A unit square whose curve loop runs clockwise, so gmsh's quads come out clockwise:
// the mesh import must reverse every zone (tested by ClockwiseGeoIsRepaired).
DefineConstant[ n = 4 ];

Point(1) = {0, 0, 0};
Point(2) = {0, 1, 0};
Point(3) = {1, 1, 0};
Point(4) = {1, 0, 0};

Line(1) = {1, 2};   // left, going up
Line(2) = {2, 3};   // top, going right
Line(3) = {3, 4};   // right, going down
Line(4) = {4, 1};   // bottom, going left

Curve Loop(1) = {1, 2, 3, 4};   // clockwise on purpose
Plane Surface(1) = {1};
Transfinite Curve{1:4} = n + 1;
Transfinite Surface{1};
Recombine Surface{1};

Physical Surface("square") = {1};
Physical Curve("left") = {1};
Physical Curve("top") = {2};
Physical Curve("right") = {3};
Physical Curve("bottom") = {4};
