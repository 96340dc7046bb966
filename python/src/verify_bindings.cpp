// The exact solutions of verify.hpp that the gas verification problems compare with, sampled
// on numpy arrays (the error norms themselves are the summary's "errors").
#include <pybind11/stl.h>

#include <string>

#include "bindings.hpp"
#include "stagger/verify.hpp"

namespace stagger_python {
namespace {

stagger::GasState gas_state(const py::dict& values) {
  stagger::GasState state;
  state.density = values["density"].cast<double>();
  state.velocity = values.contains("velocity") ? values["velocity"].cast<double>() : 0.0;
  state.pressure = values["pressure"].cast<double>();
  return state;
}

// density, velocity and pressure of `solution.state(position, t)` at every position.
template <typename Sample>
py::dict sample_states(const py::array_t<double, py::array::c_style | py::array::forcecast>& positions,
                       Sample&& sample) {
  const auto n = positions.size();
  py::array_t<double> density(n), velocity(n), pressure(n);
  const double* at = positions.data();
  for (py::ssize_t i = 0; i < n; ++i) {
    const stagger::GasState state = sample(at[i]);
    density.mutable_data()[i] = state.density;
    velocity.mutable_data()[i] = state.velocity;
    pressure.mutable_data()[i] = state.pressure;
  }
  py::dict states;
  states["density"] = density;
  states["velocity"] = velocity;
  states["pressure"] = pressure;
  return states;
}

using Positions = py::array_t<double, py::array::c_style | py::array::forcecast>;

}  // namespace

void bind_verify(py::module_& module) {
  py::class_<stagger::ExactRiemann>(module, "ExactRiemann", "The exact ideal-gas Riemann solution (Toro, ch. 4)")
      .def(py::init([](const py::dict& left, const py::dict& right, double gamma, double x0) {
             return stagger::ExactRiemann(gas_state(left), gas_state(right), gamma, x0);
           }),
           py::arg("left"), py::arg("right"), py::arg("gamma") = 1.4, py::arg("x0") = 0.5)
      .def(
          "sample",
          [](const stagger::ExactRiemann& exact, const Positions& x, double t) {
            return sample_states(x, [&](double at) { return exact.sample(at, t); });
          },
          py::arg("x"), py::arg("t"))
      .def_property_readonly("star_pressure", &stagger::ExactRiemann::star_pressure)
      .def_property_readonly("star_velocity", &stagger::ExactRiemann::star_velocity)
      .def("wave_positions", &stagger::ExactRiemann::wave_positions, py::arg("t"));

  py::class_<stagger::NohSolution>(module, "NohSolution", "Noh's implosion, cylindrical (nu = 2) or spherical (3)")
      .def(py::init<double, double, double, int>(), py::arg("gamma") = 5.0 / 3.0, py::arg("density") = 1.0,
           py::arg("speed") = 1.0, py::arg("nu") = 2)
      .def(
          "sample",
          [](const stagger::NohSolution& exact, const Positions& r, double t) {
            return sample_states(r, [&](double at) { return exact.state(at, t); });
          },
          py::arg("r"), py::arg("t"))
      .def("shock_radius", &stagger::NohSolution::shock_radius, py::arg("t"))
      .def("post_shock_density", &stagger::NohSolution::post_shock_density);

  py::class_<stagger::SedovSolution>(module, "SedovSolution", "The Sedov-Taylor point blast (Kamm & Timmes 2007)")
      .def(py::init<double, int, double, double>(), py::arg("gamma") = 1.4, py::arg("nu") = 2, py::arg("density") = 1.0,
           py::arg("energy") = 1.0)
      .def(
          "sample",
          [](const stagger::SedovSolution& exact, const Positions& r, double t) {
            return sample_states(r, [&](double at) { return exact.state(at, t); });
          },
          py::arg("r"), py::arg("t"))
      .def("shock_radius", &stagger::SedovSolution::shock_radius, py::arg("t"))
      .def("post_shock_density", &stagger::SedovSolution::post_shock_density)
      .def_property_readonly("alpha", &stagger::SedovSolution::alpha);
}

}  // namespace stagger_python
