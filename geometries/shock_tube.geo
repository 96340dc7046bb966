// Shock tube: the rectangle [0, length] x [0, height], nx x ny transfinite quads
// (the ladders keep ny = 5 and refine nx).
DefineConstant[ length = 1, height = 0.1, nx = 100, ny = 5 ];

Point(1) = {0, 0, 0};
Point(2) = {length, 0, 0};
Point(3) = {length, height, 0};
Point(4) = {0, height, 0};

Line(1) = {1, 2};   // bottom
Line(2) = {2, 3};   // right
Line(3) = {3, 4};   // top
Line(4) = {4, 1};   // left

Curve Loop(1) = {1, 2, 3, 4};   // counter-clockwise
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = nx + 1;
Transfinite Curve{2, 4} = ny + 1;
Transfinite Surface{1};
Recombine Surface{1};

Physical Surface("domain") = {1};
Physical Curve("left") = {4};
Physical Curve("right") = {2};
Physical Curve("bottom") = {1};
Physical Curve("top") = {3};
