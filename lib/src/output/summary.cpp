// summary.json, written by hand (no JSON dependency): the output contract of docs/output.md.
#include <string>

#include "io/text_format.hpp"
#include "output/material_totals.hpp"
#include "stagger/output.hpp"
#include "stagger/simulation.hpp"

namespace stagger {

namespace {
std::string named_values_object(const NamedValues& values, const std::string& indent) {
  if (values.empty()) return "{}";
  std::string text = "{\n";
  for (std::size_t i = 0; i < values.size(); ++i) {
    text += indent + "  " + io_detail::json_string(values[i].first) + ": " + io_detail::json_number(values[i].second) +
            (i + 1 < values.size() ? ",\n" : "\n");
  }
  return text + indent + "}";
}
// {"<name>": {"mass": ..., "volume": ..., "internal_energy": ..., "kinetic_energy": ...}, ...}
std::string materials_object(const Simulation& simulation) {
  using io_detail::json_number;
  const std::vector<MaterialTotals> totals = material_totals(simulation);
  std::string text = "{\n";
  for (std::size_t m = 0; m < totals.size(); ++m) {
    const MaterialTotals& t = totals[m];
    text += "    " + io_detail::json_string(t.name) + ": {\"mass\": " + json_number(t.mass) +
            ", \"volume\": " + json_number(t.volume) + ", \"internal_energy\": " + json_number(t.internal_energy) +
            ", \"kinetic_energy\": " + json_number(t.kinetic_energy) + "}" + (m + 1 < totals.size() ? ",\n" : "\n");
  }
  return text + "  }";
}
}  // namespace

void write_summary(const std::string& path, const Simulation& simulation, const RunSummary& summary) {
  using io_detail::json_number;
  using io_detail::json_string;
  const Mesh& mesh = simulation.mesh();
  const EnergyAudit energy = simulation.energy();
  const auto momentum = simulation.momentum();
  const double zones = mesh.num_zones();
  const double cycles = static_cast<double>(simulation.cycle());
  // docs/verification.md §11: zones x cycles / time of the time loop alone.
  const double rate = summary.loop_seconds > 0 ? zones * cycles / summary.loop_seconds : 0.0;

  std::string text = "{\n";
  text += "  \"scene\": " + json_string(summary.scene) + ",\n";
  text += "  \"zones\": " + std::to_string(mesh.num_zones()) + ",\n";
  text += "  \"points\": " + std::to_string(mesh.num_points()) + ",\n";
  text += "  \"cycles\": " + std::to_string(simulation.cycle()) + ",\n";
  text += "  \"t_end\": " + json_number(simulation.problem().t_end) + ",\n";
  text += "  \"time\": " + json_number(simulation.time()) + ",\n";
  text += "  \"dt\": " + json_number(simulation.dt()) + ",\n";
  text += "  \"dt_limit\": " + json_string(simulation.dt_limit()) + ",\n";
  text += "  \"wall_seconds\": " + json_number(summary.wall_seconds) + ",\n";
  text += "  \"loop_seconds\": " + json_number(summary.loop_seconds) + ",\n";
  text += "  \"zone_cycles_per_second\": " + json_number(rate) + ",\n";
  text += "  \"threads\": " + std::to_string(summary.threads) + ",\n";
  text += "  \"ranks\": " + std::to_string(summary.ranks) + ",\n";
  text += "  \"status\": " + json_string(summary.status) + ",\n";
  // The rz convention (docs/output.md): only rz runs carry it (planar summaries stay as they were).
  if (simulation.problem().options.geometry == CoordinateSystem::rz) {
    text += "  \"geometry\": \"rz\",\n";
    text += "  \"geometry_convention\": " +
            json_string("x = r, y = z, axis x = 0; masses, volumes, energies and momenta per radian") + ",\n";
  }
  // Only a stopped run has it: its last dump holds the last good state.
  if (summary.last_good_state) {
    text += "  \"last_good_state\": {\"file\": " + json_string(summary.last_dump) +
            ", \"time\": " + json_number(summary.last_dump_time) + "},\n";
  }
  text += "  \"energy\": {\n";
  text += "    \"initial\": " + json_number(energy.initial) + ",\n";
  text += "    \"final\": " + json_number(energy.total) + ",\n";
  text += "    \"kinetic\": " + json_number(energy.kinetic) + ",\n";
  text += "    \"internal\": " + json_number(energy.internal) + ",\n";
  text += "    \"boundary_work\": " + json_number(energy.boundary_work) + ",\n";
  text += "    \"source_work\": " + json_number(energy.source_work) + ",\n";
  text += "    \"ale_fixup\": " + json_number(energy.ale_fixup) + ",\n";
  text += "    \"relative_error\": " + json_number(energy.relative_error) + "\n";
  text += "  },\n";
  text += "  \"momentum\": [" + json_number(momentum[0]) + ", " + json_number(momentum[1]) + "],\n";
  text += "  \"materials\": " + materials_object(simulation) + ",\n";
  text += "  \"errors\": " + named_values_object(summary.errors, "  ") + ",\n";
  text += "  \"diagnostics\": " + named_values_object(summary.diagnostics, "  ") + "\n";
  text += "}\n";
  write_file_atomically(path, text);
}

}  // namespace stagger
