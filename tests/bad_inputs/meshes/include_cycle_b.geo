// Includes include_cycle_a.geo, which includes this file.
Include "unit_square.geo";
Include "include_cycle_a.geo";
