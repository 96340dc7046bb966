// Scenes: load_scene (scene.hpp) with overrides, and what a loaded scene tells before it runs.
#include <pybind11/stl.h>

#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "bindings.hpp"

namespace stagger_python {
namespace {

py::dict gas_state(const stagger::GasState& state) {
  py::dict values;
  values["density"] = state.density;
  values["velocity"] = state.velocity;
  values["pressure"] = state.pressure;
  return values;
}

// The resolved [verification] parameters of the gas references as a dict (the other references
// carry their name only: their parameters are material constants of the scene).
py::dict verification_parameters(const stagger::VerificationSetup& setup) {
  py::dict values;
  std::visit(
      [&](const auto& p) {
        using P = std::decay_t<decltype(p)>;
        if constexpr (std::is_same_v<P, stagger::ShockTubeReference>) {
          values["left"] = gas_state(p.left);
          values["right"] = gas_state(p.right);
          values["gamma"] = p.gamma;
          values["x0"] = p.x0;
        } else if constexpr (std::is_same_v<P, stagger::NohReference>) {
          values["gamma"] = p.gamma;
          values["density"] = p.density;
          values["speed"] = p.speed;
          values["nu"] = p.nu;
        } else if constexpr (std::is_same_v<P, stagger::SedovReference>) {
          values["gamma"] = p.gamma;
          values["density"] = p.density;
          values["energy_quarter"] = p.energy_quarter;
          values["nu"] = p.nu;
        } else if constexpr (std::is_same_v<P, stagger::SaltzmanReference>) {
          values["piston_speed"] = p.piston_speed;
          values["gamma"] = p.gamma;
          values["density"] = p.density;
        } else if constexpr (std::is_same_v<P, stagger::TaylorGreenReference>) {
          values["p0"] = p.p0;
        }
      },
      setup.parameters);
  return values;
}

py::dict output_settings(const stagger::RunControl& control) {
  py::dict values;
  values["directory"] = control.output_directory;
  values["name"] = control.name;
  values["dump_interval"] = control.dump_interval;
  values["dumps"] = control.dumps;
  values["history_every"] = control.history_every;
  values["checkpoint_every_cycles"] = control.checkpoint_every_cycles;
  values["checkpoint_every_seconds"] = control.checkpoint_every_seconds;
  values["checkpoints"] = control.checkpoints;
  return values;
}

}  // namespace

void bind_scene(py::module_& module) {
  py::class_<stagger::Scene, SceneHandle>(module, "Scene", "A scene file read, meshed and validated")
      .def_readonly("file", &stagger::Scene::file)
      .def_readonly("notes", &stagger::Scene::notes)
      .def_readonly("warnings", &stagger::Scene::warnings)
      .def_property_readonly("name", [](const stagger::Scene& scene) { return scene.problem.name; })
      .def_property_readonly("t_end", [](const stagger::Scene& scene) { return scene.problem.t_end; })
      .def_property_readonly("zones", [](const stagger::Scene& scene) { return scene.problem.mesh.num_zones(); })
      .def_property_readonly("points", [](const stagger::Scene& scene) { return scene.problem.mesh.num_points(); })
      .def_property_readonly("output", [](const stagger::Scene& scene) { return output_settings(scene.control); })
      .def_property_readonly("reference", [](const stagger::Scene& scene) { return scene.verification.name; })
      .def_property_readonly("reference_parameters",
                             [](const stagger::Scene& scene) { return verification_parameters(scene.verification); })
      .def("describe", [](const stagger::Scene& scene) { return stagger::describe(scene); });

  module.def(
      "load_scene",
      [](const std::string& path, const std::vector<std::pair<std::string, std::string>>& overrides) {
        py::gil_scoped_release release;  // meshing a .geo file can take a while
        return std::make_shared<stagger::Scene>(stagger::load_scene(path, overrides));
      },
      py::arg("path"), py::arg("overrides") = std::vector<std::pair<std::string, std::string>>{},
      "Reads, meshes and validates a scene; overrides are (key, TOML value text) pairs, as --set.");
}

}  // namespace stagger_python
