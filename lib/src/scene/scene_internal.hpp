#pragma once
// Pieces of the scene reader shared between its translation units.
#include <optional>
#include <string>
#include <vector>

#include "stagger/scene.hpp"
#include "stagger/verify.hpp"
#include "toml_reader.hpp"

namespace stagger::scene_detail {

/// Reads [mesh], meshes it (meshgen + build_mesh) and returns the mesh; notes are appended.
Mesh read_mesh_section(Section& mesh, const std::string& scene_file, std::vector<std::string>& notes);

/// What [sources] resolved that [verification] reuses (the same manufactured solution).
struct SourceContext {
  std::string kind;  ///< "" if no [sources]
  std::optional<AccuracyParameters> accuracy;
};

/// Reads [sources] into problem.sources.
SourceContext read_sources_section(Section& sources, Problem& problem);
/// Reads [verification] into control.reference and its parameters into `setup`.
void read_verification_section(Section& verification, const Problem& problem, const SourceContext& sources,
                               RunControl& control, VerificationSetup& setup);

}  // namespace stagger::scene_detail
