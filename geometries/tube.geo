// Tube: the full annulus ri <= r <= ro, equal-angle transfinite mesh with n_theta zones
// around (a multiple of 4: four quarter patches) and n_r zones across.
DefineConstant[ ri = 0.08, ro = 0.1, n_theta = 64, n_r = 8 ];

Point(1) = {0, 0, 0};   // centre (not meshed)
// Inner (2..5) and outer (6..9) points at 0, 90, 180 and 270 degrees.
Point(2) = {ri, 0, 0};  Point(3) = {0, ri, 0};  Point(4) = {-ri, 0, 0};  Point(5) = {0, -ri, 0};
Point(6) = {ro, 0, 0};  Point(7) = {0, ro, 0};  Point(8) = {-ro, 0, 0};  Point(9) = {0, -ro, 0};

// Arcs of less than pi each (gmsh's Circle needs that).
Circle(1) = {2, 1, 3};  Circle(2) = {3, 1, 4};  Circle(3) = {4, 1, 5};  Circle(4) = {5, 1, 2};
Circle(5) = {6, 1, 7};  Circle(6) = {7, 1, 8};  Circle(7) = {8, 1, 9};  Circle(8) = {9, 1, 6};
// Radial cuts between the quarter patches.
Line(9) = {2, 6};  Line(10) = {3, 7};  Line(11) = {4, 8};  Line(12) = {5, 9};

// Four counter-clockwise quarter patches.
Curve Loop(1) = {9, 5, -10, -1};   Plane Surface(1) = {1};
Curve Loop(2) = {10, 6, -11, -2};  Plane Surface(2) = {2};
Curve Loop(3) = {11, 7, -12, -3};  Plane Surface(3) = {3};
Curve Loop(4) = {12, 8, -9, -4};   Plane Surface(4) = {4};

Transfinite Curve{1, 2, 3, 4, 5, 6, 7, 8} = n_theta / 4 + 1;
Transfinite Curve{9, 10, 11, 12} = n_r + 1;
Transfinite Surface{1:4};
Recombine Surface{1:4};

Physical Surface("tube") = {1:4};
Physical Curve("inner") = {1:4};
Physical Curve("outer") = {5:8};
