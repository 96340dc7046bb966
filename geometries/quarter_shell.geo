// Quarter of a shell: the annulus ri <= r <= ro, 0 <= theta <= pi/2, meshed transfinite
// with equal angles (n_theta zones around) and equal radial steps (n_r zones across).
// Override any parameter by name, e.g. stagger mesh quarter_shell.geo --set n_theta=40.
DefineConstant[ ri = 0.08, ro = 0.1, n_theta = 20, n_r = 16 ];

Point(1) = {0, 0, 0};    // centre of the arcs (not meshed)
Point(2) = {ri, 0, 0};
Point(3) = {ro, 0, 0};
Point(4) = {0, ro, 0};
Point(5) = {0, ri, 0};

Line(1) = {2, 3};        // start: the y = 0 side
Circle(2) = {3, 1, 4};   // outer arc
Line(3) = {4, 5};        // end: the x = 0 side
Circle(4) = {5, 1, 2};   // inner arc

Curve Loop(1) = {1, 2, 3, 4};   // counter-clockwise
Plane Surface(1) = {1};

// Transfinite circles are split at equal parameter, i.e. equal angle; the transfinite
// (Coons) interpolation then puts every interior node on its circle and its ray.
Transfinite Curve{2, 4} = n_theta + 1;
Transfinite Curve{1, 3} = n_r + 1;
Transfinite Surface{1};
Recombine Surface{1};

Physical Surface("shell") = {1};
Physical Curve("inner") = {4};
Physical Curve("outer") = {2};
Physical Curve("start") = {1};
Physical Curve("end") = {3};
