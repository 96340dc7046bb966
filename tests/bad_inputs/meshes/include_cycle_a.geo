// Includes include_cycle_b.geo, which includes this file.
Include "include_cycle_b.geo";
