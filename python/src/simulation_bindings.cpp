// The Python Simulation: set-up from a Scene, the state as numpy views, the mesh, the history
// and summary, dumps, checkpoints (simulation.hpp, output.hpp; docs/python.md).
#include <omp.h>
#include <pybind11/stl.h>
#include <unistd.h>

#include <atomic>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "simulation_handle.hpp"

namespace stagger_python {
namespace {

// The Simulation of a scene; its set-up errors are located at the scene file, as `stagger run`
// reports them.
stagger::Simulation set_up(const stagger::Scene& scene) {
  try {
    return stagger::Simulation(scene.problem);
  } catch (const stagger::Error& failure) {
    throw stagger::Error(scene.file + ": set-up failed: " + failure.what());
  }
}

// Every state array of simulation.hpp by name.
struct FieldAccessor {
  const char* name;
  std::span<const double> (stagger::Simulation::*values)() const;
};
constexpr FieldAccessor field_accessors[] = {
    {"x", &stagger::Simulation::x},
    {"y", &stagger::Simulation::y},
    {"velocity_x", &stagger::Simulation::velocity_x},
    {"velocity_y", &stagger::Simulation::velocity_y},
    {"point_mass", &stagger::Simulation::point_mass},
    {"zone_mass", &stagger::Simulation::zone_mass},
    {"zone_area", &stagger::Simulation::zone_area},
    {"density", &stagger::Simulation::density},
    {"pressure", &stagger::Simulation::pressure},
    {"specific_internal_energy", &stagger::Simulation::specific_internal_energy},
    {"artificial_viscosity", &stagger::Simulation::artificial_viscosity},
    {"sound_speed", &stagger::Simulation::sound_speed},
    {"stress_xx", &stagger::Simulation::stress_xx},
    {"stress_yy", &stagger::Simulation::stress_yy},
    {"stress_xy", &stagger::Simulation::stress_xy},
    {"plastic_strain", &stagger::Simulation::plastic_strain},
    {"burn_fraction", &stagger::Simulation::burn_fraction},
};

std::vector<std::string> field_names(const stagger::Simulation& simulation) {
  std::vector<std::string> names;
  for (const auto& field : field_accessors)
    if (!(simulation.*field.values)().empty()) names.emplace_back(field.name);
  return names;
}

py::array field_view(py::object self, const std::string& name) {
  const stagger::Simulation& simulation = self.cast<SimulationHandle&>().simulation;
  for (const auto& field : field_accessors) {
    if (name != field.name) continue;
    const std::span<const double> values = (simulation.*field.values)();
    if (values.empty()) throw py::key_error("field '" + name + "' is not part of this run (no strength or burn)");
    return read_only_view(values, self);
  }
  std::string known;
  for (const auto& field : field_accessors) known += std::string(known.empty() ? "" : ", ") + field.name;
  throw py::key_error("no field '" + name + "'; the fields are " + known);
}

template <typename T>
py::array index_view(const std::vector<T>& values, py::handle owner) {
  return read_only_view(std::span<const T>(values), owner);
}

// The topology of mesh.hpp as read-only views; the tags' edges as (n, 2) copies.
py::dict mesh_arrays(py::object self) {
  const stagger::Mesh& mesh = self.cast<SimulationHandle&>().simulation.mesh();
  py::dict arrays;
  arrays["zone_corner_begin"] = index_view(mesh.zone_corner_begin, self);
  arrays["corner_point"] = index_view(mesh.corner_point, self);
  arrays["corner_zone"] = index_view(mesh.corner_zone, self);
  arrays["point_corner_begin"] = index_view(mesh.point_corner_begin, self);
  arrays["point_corners"] = index_view(mesh.point_corners, self);
  arrays["zone_region"] = index_view(mesh.zone_region, self);
  arrays["region_names"] = mesh.region_names;
  py::dict tags;
  for (const stagger::BoundaryTag& tag : mesh.tags) {
    py::array_t<stagger::Index> edges({static_cast<py::ssize_t>(tag.edges.size()), py::ssize_t{2}});
    if (!tag.edges.empty())
      std::memcpy(edges.mutable_data(), tag.edges.data(), tag.edges.size() * sizeof(tag.edges[0]));
    py::dict entry;
    entry["edges"] = edges;
    entry["points"] = py::array_t<stagger::Index>(static_cast<py::ssize_t>(tag.points.size()), tag.points.data());
    tags[py::str(tag.name)] = entry;
  }
  arrays["tags"] = tags;
  arrays["source"] = mesh.source;
  return arrays;
}

// summary.json's text for the current state: write_summary() is the one formatter of it, so
// the dict Python reads is the CLI's (through a temporary file, removed at once).
std::string summary_json(SimulationHandle& handle) {
  stagger::RunSummary summary = handle.run_summary;
  const stagger::Simulation& simulation = handle.simulation;
  summary.scene = simulation.problem().name.empty() ? handle.control.name : simulation.problem().name;
  summary.threads = omp_get_max_threads();
  summary.errors.clear();
  summary.diagnostics.clear();
  if (handle.control.reference) handle.control.reference(simulation, summary.errors, summary.diagnostics);
  static std::atomic<long> serial{0};
  const auto path = std::filesystem::temp_directory_path() /
                    ("stagger-summary-" + std::to_string(::getpid()) + "-" + std::to_string(serial++) + ".json");
  stagger::write_summary(path.string(), simulation, summary);
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  std::filesystem::remove(path);
  return text.str();
}

py::dict energy_audit(const stagger::Simulation& simulation) {
  const stagger::EnergyAudit energy = simulation.energy();
  py::dict values;
  values["kinetic"] = energy.kinetic;
  values["internal"] = energy.internal;
  values["total"] = energy.total;
  values["initial"] = energy.initial;
  values["boundary_work"] = energy.boundary_work;
  values["source_work"] = energy.source_work;
  values["ale_fixup"] = energy.ale_fixup;
  values["relative_error"] = energy.relative_error;
  return values;
}

void restore_checkpoint(SimulationHandle& handle, const py::bytes& blob, const std::string& source) {
  const std::string data = blob;
  handle.simulation.restore(data, source);
  handle.restart_history();
}

}  // namespace

SimulationHandle::SimulationHandle(const stagger::Scene& scene)
    : simulation(set_up(scene)), control(scene.control), scene_file(scene.file) {
  restart_history();
}

void SimulationHandle::record_history() {
  history.record(simulation);
  last_history_cycle = simulation.cycle();
}

void SimulationHandle::restart_history() {
  history = stagger::HistoryWriter("");
  record_history();
}

void bind_simulation(py::module_& module) {
  using stagger::Simulation;
  auto state = [](SimulationHandle& handle) -> const Simulation& { return handle.simulation; };
  py::class_<SimulationHandle>(module, "Simulation", "A scene being run (stagger::Simulation)")
      .def(py::init([](const SceneHandle& scene) { return new SimulationHandle(*scene); }), py::arg("scene"))
      .def("advance", &advance, py::arg("until") = py::none(), py::arg("callback") = py::none(),
           py::arg("progress") = false)
      .def("run_with_files", &run_with_files, py::arg("directory"), py::arg("restart") = "",
           py::arg("callback") = py::none(), py::arg("progress") = false)
      .def(
          "step",
          [](SimulationHandle& handle) {
            {
              py::gil_scoped_release release;
              handle.simulation.step();
            }
            handle.record_history();
          },
          "One cycle with the controlled dt (recorded in the history).")
      .def_property_readonly("time", [=](SimulationHandle& h) { return state(h).time(); })
      .def_property_readonly("cycle", [=](SimulationHandle& h) { return state(h).cycle(); })
      .def_property_readonly("dt", [=](SimulationHandle& h) { return state(h).dt(); })
      .def_property_readonly("dt_limit", [=](SimulationHandle& h) { return state(h).dt_limit(); })
      .def_property_readonly("finished", [=](SimulationHandle& h) { return state(h).finished(); })
      .def_property_readonly("t_end", [=](SimulationHandle& h) { return state(h).problem().t_end; })
      .def_property_readonly("has_strength", [=](SimulationHandle& h) { return state(h).has_strength(); })
      .def_property_readonly("has_burn", [=](SimulationHandle& h) { return state(h).has_burn(); })
      .def_readonly("scene_file", &SimulationHandle::scene_file)
      .def_readonly("history_file", &SimulationHandle::history_file)
      .def("field_names", [=](SimulationHandle& h) { return field_names(state(h)); })
      .def("field", &field_view, py::arg("name"), "A read-only numpy view of a state array (no copy).")
      .def("mesh", &mesh_arrays)
      .def("energy", [=](SimulationHandle& h) { return energy_audit(state(h)); })
      .def("momentum", [=](SimulationHandle& h) { return state(h).momentum(); })
      .def("history_text", [](SimulationHandle& h) { return h.history.text(); })
      .def("summary_json", &summary_json)
      .def("write_vtu", [=](SimulationHandle& h, const std::string& path) { stagger::write_vtu(path, state(h)); })
      .def("write_zone_csv",
           [=](SimulationHandle& h, const std::string& path) { stagger::write_zone_csv(path, state(h)); })
      .def("checkpoint", [=](SimulationHandle& h) { return py::bytes(state(h).checkpoint()); })
      .def("restore", &restore_checkpoint, py::arg("blob"), py::arg("source") = "checkpoint");
}

}  // namespace stagger_python
