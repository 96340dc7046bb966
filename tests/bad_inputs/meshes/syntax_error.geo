// A .geo with a syntax error on line 3 (missing ';' and a bad token).
Point(1) = {0, 0, 0, 0.1};
Point(2) = {1, 0, 0, 0.1} Line(1) = {1, 2;
