// A .geo that runs a shell command (refused unless mesh.allow_geo_commands = true).
Include "unit_square.geo";
/* SystemCall in a comment is harmless */ text = "SystemCall in a string too";
SystemCall "touch stagger_was_here";
