// Merges a "mesh" that gmsh would run as a script.
Merge "script.msh";
