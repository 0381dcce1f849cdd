// The pieces of the Python module's C++ layer. It only translates: models in, library calls,
// numpy arrays, strings and Python exceptions out.
#pragma once

#include <pybind11/pybind11.h>

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "nbar/analysis/analysis.hpp"
#include "nbar/io/model_file.hpp"

namespace nbar::python {

namespace py = pybind11;

// A model as Python holds it: the file's text and source map, for locating errors, and the
// compiled mechanism every analysis shares.
struct PyModel {
  io::LoadedModel file;
  std::shared_ptr<const Mechanism> mechanism;
  std::string import_dir;  // where a model file's imports are read from; empty for a model from text
  // Model.with_points and Model.with_lengths, in the model's units, in the order made: a pickled
  // model is its text, parsed again, with these edits replayed.
  std::vector<std::pair<std::string, std::array<double, 2>>> moved_points;
  std::vector<std::pair<std::string, double>> set_lengths;
};

// Parses and compiles; an invalid model raises nbar.ModelError at file:line:column.
PyModel compile_model(io::LoadedModel loaded);

// nbar::Error -> the nbar.errors class of its kind, with message, file, line, column, entity.
void register_error_translation(py::module_& m);
// A message or text of the core's with the command line's options named as Python's arguments
// ("--max-steps" as "max_steps=").
std::string in_python_words(std::string message);
// The nbar.errors instance of an error, for a call that reports several (solve_many), and the
// InternalError any other C++ exception crosses as.
py::object python_error(const Error& e);
Error internal_error(const std::exception& e);
// The same error with the model file's place of its entity, when it has none of its own.
Error located(const PyModel& model, const Error& error);

// A result's warnings as (code, step, message) tuples.
py::list warning_list(const std::vector<Warning>& warnings);

// Runs `work` with the GIL released. Ctrl-C (a Jupyter interrupt) cancels `control`'s token,
// and the call then raises KeyboardInterrupt; `timeout` (s) sets a deadline.
void run_interruptible(RunControl& control, std::optional<double> timeout, const std::function<void()>& work);

void bind_model(py::module_& m);
void bind_analysis(py::module_& m);
void bind_explain(py::module_& m);
void bind_synthesis(py::module_& m);
void bind_equilibrium(py::module_& m);

}  // namespace nbar::python
