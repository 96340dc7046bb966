// Found by scripts/fuzz_geo.py: gmsh 4.8 aborts on a double free (glibc prints it on stderr).
BooleanFragments{ Surface{:}; Delete; }{}
Include "unit_square.geo";