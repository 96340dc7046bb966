// The compiled part of the `stagger` Python package (docs/python.md): thin bindings of the
// public C++ API (docs/api.md); python/stagger/__init__.py builds the user-facing layer on it.
#include <omp.h>

#include "bindings.hpp"
#include "stagger/error.hpp"

PYBIND11_MODULE(_stagger, module) {
  namespace py = pybind11;
  module.doc() = "Stagger's C++ API (docs/api.md), bound for the stagger package";
  // stagger::Error, the library's one exception type, as a RuntimeError subclass.
  py::register_exception<stagger::Error>(module, "Error", PyExc_RuntimeError);
  module.def(
      "set_threads", [](int threads) { omp_set_num_threads(threads); }, py::arg("threads"),
      "Sets the number of OpenMP threads of the steps (the results are bitwise the same for any).");
  module.def(
      "threads", [] { return omp_get_max_threads(); }, "The number of OpenMP threads a step uses.");
  stagger_python::bind_scene(module);
  stagger_python::bind_simulation(module);
  stagger_python::bind_verify(module);
}
