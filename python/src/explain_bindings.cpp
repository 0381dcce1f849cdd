// The step-by-step explanation (nbar/analysis/explain.hpp) from Python.
#include "bindings.hpp"

namespace nbar::python {

void bind_explain(py::module_&) {}

}  // namespace nbar::python
