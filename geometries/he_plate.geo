// An HE slab driving a metal plate (apps/scenes/he_plate.toml), cm: the explosive fills
// 0 <= x <= he, the plate he <= x <= he + plate, both 0 <= y <= h, as two transfinite
// patches sharing the interface line x = he (one mesh, two regions, conforming points).
// Zones: n_he and n_plate along x, n_y across.
DefineConstant[ he = 0.5, plate = 0.2, h = 0.1, n_he = 50, n_plate = 20, n_y = 2 ];

Point(1) = {0, 0, 0};
Point(2) = {he, 0, 0};
Point(3) = {he + plate, 0, 0};
Point(4) = {he + plate, h, 0};
Point(5) = {he, h, 0};
Point(6) = {0, h, 0};

Line(1) = {1, 2};  // bottom of the explosive
Line(2) = {2, 3};  // bottom of the plate
Line(3) = {3, 4};  // free face of the plate
Line(4) = {4, 5};  // top of the plate
Line(5) = {5, 6};  // top of the explosive
Line(6) = {6, 1};  // the detonation wall x = 0
Line(7) = {2, 5};  // interface (untagged: interior to the mesh)

Curve Loop(1) = {1, 7, 5, 6};   // counter-clockwise
Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7};  // counter-clockwise
Plane Surface(2) = {2};

Transfinite Curve{1, 5} = n_he + 1;
Transfinite Curve{2, 4} = n_plate + 1;
Transfinite Curve{3, 6, 7} = n_y + 1;
Transfinite Surface{1, 2};
Recombine Surface{1, 2};

Physical Surface("explosive") = {1};
Physical Surface("plate") = {2};
Physical Curve("left") = {6};
Physical Curve("right") = {3};
Physical Curve("bottom") = {1, 2};
Physical Curve("top") = {4, 5};
