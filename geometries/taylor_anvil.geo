// The Taylor anvil rod in rz (apps/scenes/taylor_anvil.toml, docs/solids.md §9): the half
// section 0 <= r <= R0, 0 <= z <= L0 of a copper rod standing on the rigid wall z = 0 (SI
// units, m; x = r, y = z, the axis is x = 0), meshed as a structured grid of quads with n
// zones across the radius and 10 n along the length (the benchmark's square zones:
// L0 / (10 n) = 3.24 mm / n against R0 / n = 3.2 mm / n).
DefineConstant[ radius = 0.0032, length = 0.0324, n = 10 ];

Point(1) = {0, 0, 0};
Point(2) = {radius, 0, 0};
Point(3) = {radius, length, 0};
Point(4) = {0, length, 0};
Line(1) = {1, 2};  Line(2) = {2, 3};  Line(3) = {3, 4};  Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

Transfinite Curve{1, 3} = n + 1;
Transfinite Curve{2, 4} = 10 * n + 1;
Transfinite Surface{1};
Recombine Surface{1};

Physical Surface("domain") = {1};
Physical Curve("bottom") = {1};  // the impact face, on the wall z = 0
Physical Curve("right") = {2};   // the free side r = R0
Physical Curve("top") = {3};     // the free end
Physical Curve("left") = {4};    // the axis r = 0
