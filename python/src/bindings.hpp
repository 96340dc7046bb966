#pragma once
// The pieces of the `stagger._stagger` extension module (docs/python.md): each binds one header
// group of the public C++ API; module.cpp assembles them.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <span>

#include "stagger/scene.hpp"

namespace stagger_python {

namespace py = pybind11;

/// A loaded scene, shared by the Python Scene object and the simulations made from it.
using SceneHandle = std::shared_ptr<stagger::Scene>;

/// A read-only numpy view of `values` (no copy); `owner` keeps the memory alive.
template <typename T>
py::array read_only_view(std::span<const T> values, py::handle owner) {
  static const T empty{};
  py::array_t<T> view({static_cast<py::ssize_t>(values.size())}, {static_cast<py::ssize_t>(sizeof(T))},
                      values.empty() ? &empty : values.data(), owner);
  view.attr("setflags")(py::arg("write") = false);
  return view;
}

void bind_scene(py::module_& module);       // scene_bindings.cpp
void bind_simulation(py::module_& module);  // simulation_bindings.cpp
void bind_verify(py::module_& module);      // verify_bindings.cpp

}  // namespace stagger_python
