// Includes itself.
Include "unit_square.geo";
Include "self_include.geo";
