// A .geo that ends the process.
Include "unit_square.geo";
Exit;
