// The water-air shock tube (apps/scenes/water_air.toml), m: water fills 0 <= x <= xi, air
// xi <= x <= 1, both 0 <= y <= h, as two transfinite patches sharing the interface line
// x = xi (one mesh, two regions, conforming points). Zones: n_water and n_air along x, n_y across.
DefineConstant[ xi = 0.7, h = 0.01, n_water = 70, n_air = 30, n_y = 1 ];

Point(1) = {0, 0, 0};
Point(2) = {xi, 0, 0};
Point(3) = {1, 0, 0};
Point(4) = {1, h, 0};
Point(5) = {xi, h, 0};
Point(6) = {0, h, 0};

Line(1) = {1, 2};  // bottom of the water
Line(2) = {2, 3};  // bottom of the air
Line(3) = {3, 4};  // right wall
Line(4) = {4, 5};  // top of the air
Line(5) = {5, 6};  // top of the water
Line(6) = {6, 1};  // left wall
Line(7) = {2, 5};  // interface (untagged: interior to the mesh)

Curve Loop(1) = {1, 7, 5, 6};   // counter-clockwise
Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7};  // counter-clockwise
Plane Surface(2) = {2};

Transfinite Curve{1, 5} = n_water + 1;
Transfinite Curve{2, 4} = n_air + 1;
Transfinite Curve{3, 6, 7} = n_y + 1;
Transfinite Surface{1, 2};
Recombine Surface{1, 2};

Physical Surface("water") = {1};
Physical Surface("air") = {2};
Physical Curve("left") = {6};
Physical Curve("right") = {3};
Physical Curve("bottom") = {1, 2};
Physical Curve("top") = {4, 5};
