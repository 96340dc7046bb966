// A .geo that writes a file with Printf.
Include "unit_square.geo";
Printf("n = %g", 4);
Printf("n = %g", 4) > "written_by_geo.txt";
