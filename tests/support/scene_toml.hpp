#pragma once
// Scene text (docs/scenes.md) for the tests that write a scene file, section by section:
// each function returns whole lines, so a scene is their concatenation.
#include <string>

namespace stagger::testing::toml {

inline std::string time(const std::string& end) {
  return "[time]\nend = " + end + "\n";
}

/// The rectangle generator; `x` and `y` as TOML arrays, e.g. "[0.0, 1.0]".
inline std::string rectangle(const std::string& x, const std::string& y, int nx, int ny) {
  return "[mesh]\ngenerator = \"rectangle\"\nx = " + x + "\ny = " + y + "\nnx = " + std::to_string(nx) +
         "\nny = " + std::to_string(ny) + "\n";
}

/// The material "gas": an ideal gas with gamma = 1.4.
inline std::string ideal_gas() {
  return "[[material]]\nname = \"gas\"\neos = \"ideal_gas\"\ngamma = 1.4\n";
}

/// The material "copper" of apps/scenes/piston.toml (Mie-Gruneisen, SI units), without strength.
inline std::string copper() {
  return "[[material]]\nname = \"copper\"\neos = \"mie_gruneisen\"\nrho0 = 8930.0\na0 = 3940.0\ngamma0 = 2.0\ns = "
         "1.49\n";
}

/// `material` filling the region "domain"; `density` and `pressure` as TOML values.
inline std::string region(const std::string& material, const std::string& density, const std::string& pressure) {
  return "[[region]]\nname = \"domain\"\nmaterial = \"" + material + "\"\ndensity = " + density +
         "\npressure = " + pressure + "\n";
}

inline std::string gas_region(const std::string& density = "1.0", const std::string& pressure = "1.0") {
  return region("gas", density, pressure);
}

/// Walls on `tags` (a TOML array), all four sides of a rectangle by default.
inline std::string walls(const std::string& tags = R"(["left", "right", "bottom", "top"])") {
  return "[[boundary]]\ntags = " + tags + "\ntype = \"wall\"\n";
}

/// A wall along the bottom of a rectangle, its other sides free.
inline std::string bottom_wall_free_elsewhere() {
  return "[[boundary]]\ntag = \"bottom\"\ntype = \"wall\"\n[[boundary]]\ntags = [\"left\", \"right\", \"top\"]\ntype = "
         "\"free\"\n";
}

}  // namespace stagger::testing::toml
