// The extension module nbar._nbar, imported by the nbar package (python/nbar/__init__.py).
#include "bindings.hpp"
#include "nbar/version.hpp"

PYBIND11_MODULE(_nbar, m) {
  m.doc() = "nbar's C++ core: models, the analysis pipeline, the explanation, synthesis and pictures";
  m.attr("__version__") = nbar::kVersion;
  nbar::python::register_error_translation(m);
  nbar::python::bind_model(m);
  nbar::python::bind_analysis(m);
  nbar::python::bind_explain(m);
  nbar::python::bind_synthesis(m);
  nbar::python::bind_equilibrium(m);
}
