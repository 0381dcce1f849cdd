// Errors cross into Python as the nbar.errors classes; Ctrl-C crosses into C++ as a cancelled
// token.
#include <pybind11/pybind11.h>

#include <atomic>
#include <csignal>
#include <exception>
#include <string>
#include <utility>

#include "bindings.hpp"
#include "nbar/kinematics/continuation.hpp"

namespace nbar::python {

namespace {

const char* error_class(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::InvalidModel: return "ModelError";
    case ErrorKind::UndefinedLaw: return "UndefinedLawError";
    case ErrorKind::BadInput: return "BadInputError";
    case ErrorKind::CannotAssemble: return "AssemblyError";
    case ErrorKind::StoppedAtLimit: return "LimitError";
    case ErrorKind::Cancelled: return "Cancelled";
    case ErrorKind::Internal: return "InternalError";
  }
  return "Error";
}

}  // namespace

// The core's messages and the synthesis table name the command line's options where one raises a
// limit or lists more; in Python the same thing is an argument.
std::string in_python_words(std::string message) {
  static const std::pair<const char*, const char*> kOptionArguments[] = {
      {"--max-steps", "max_steps="}, {"--all lists them", "all=True lists them"}, {"--top N", "top=N"}};
  for (const auto& [option, argument] : kOptionArguments) {
    const std::string from = option;
    for (std::size_t at = message.find(from); at != std::string::npos; at = message.find(from, at))
      message.replace(at, from.size(), argument);
  }
  return message;
}

namespace {

py::object error_class_of(const Error& e) { return py::module_::import("nbar.errors").attr(error_class(e.kind())); }

}  // namespace

py::object python_error(const Error& e) {
  py::object file = e.file().empty() ? py::none() : py::object(py::str(e.file()));
  py::object line = e.mark().line > 0 ? py::object(py::int_(e.mark().line)) : py::none();
  py::object column = e.mark().column > 0 ? py::object(py::int_(e.mark().column)) : py::none();
  py::object entity = py::none();
  if (e.where().kind != EntityRef::Kind::Model && e.where().index >= 0)
    entity = py::make_tuple(to_string(e.where().kind), e.where().index);
  return error_class_of(e)(in_python_words(e.message()), py::arg("kind") = to_string(e.kind()), py::arg("file") = file,
                           py::arg("line") = line, py::arg("column") = column, py::arg("entity") = entity);
}

Error internal_error(const std::exception& e) {
  return Error(ErrorKind::Internal, std::string("internal error in nbar (") + e.what() +
                                        "); please report it, with the model or task that caused it");
}

namespace {

void raise(const Error& e) {
  const py::object instance = python_error(e);
  PyErr_SetObject(error_class_of(e).ptr(), instance.ptr());
}

// The token Ctrl-C cancels while a computation runs with the GIL released.
std::atomic<const CancelToken*> interrupt_target{nullptr};
std::atomic<bool> interrupted{false};

extern "C" void on_interrupt(int) {
  interrupted.store(true);
  if (const CancelToken* token = interrupt_target.load()) token->cancel();
}

// Called with the GIL held.
bool on_main_thread() {
  py::object threading = py::module_::import("threading");
  return threading.attr("current_thread")().is(threading.attr("main_thread")());
}

}  // namespace

// Any other C++ exception is a defect of nbar (the library turns its own problems and those of
// the libraries it calls into Error): it crosses as nbar.InternalError, never as pybind11's
// RuntimeError or ValueError, which `except nbar.Error` would miss.
void raise_internal(const std::exception& e) { raise(internal_error(e)); }

void register_error_translation(py::module_&) {
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      raise(e);
    } catch (const py::error_already_set&) {
      throw;  // a Python exception already (KeyboardInterrupt, one from a callback): pybind11 restores it
    } catch (const py::builtin_exception&) {
      throw;  // pybind11's own (StopIteration, a failed cast): pybind11 maps it
    } catch (const std::exception& e) {
      raise_internal(e);
    }
  });
}

Error located(const PyModel& model, const Error& error) {
  // Bad input is about the call's arguments, a cancellation about time, an internal error about
  // nbar: none has a place in the file.
  if (!error.file().empty() || error.kind() == ErrorKind::BadInput || error.kind() == ErrorKind::Cancelled ||
      error.kind() == ErrorKind::Internal)
    return error;
  // A stop at a limit about no entity in particular (draw(at=...), explain(step=...)) is placed
  // where solve() and the command line place a stopped sweep: the sweep's or first driver's line.
  const bool sweep_stop = error.kind() == ErrorKind::StoppedAtLimit && error.where().kind == EntityRef::Kind::Model;
  const SourceMark mark = sweep_stop && model.file.source.sweep_stop().line > 0 ? model.file.source.sweep_stop()
                                                                                : model.file.source.find(error.where());
  return Error(error.kind(), error.message(), error.where(), model.file.source.file, mark);
}

void run_interruptible(RunControl& control, std::optional<double> timeout, const std::function<void()>& work) {
  if (timeout) {
    if (!(*timeout > 0)) throw Error(ErrorKind::BadInput, "timeout must be a positive number of seconds");
    control.token.set_time_budget(std::chrono::duration<double>(*timeout));
  }
  const bool catch_interrupt = on_main_thread();
  struct sigaction previous {};
  if (catch_interrupt) {
    interrupted.store(false);
    interrupt_target.store(&control.token);
    struct sigaction action {};
    action.sa_handler = on_interrupt;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, &previous);
  }
  std::exception_ptr failure;
  {
    py::gil_scoped_release release;
    try {
      work();
    } catch (...) {
      failure = std::current_exception();
    }
  }
  if (catch_interrupt) {
    sigaction(SIGINT, &previous, nullptr);
    interrupt_target.store(nullptr);
    if (interrupted.exchange(false)) {
      PyErr_SetNone(PyExc_KeyboardInterrupt);
      throw py::error_already_set();
    }
  }
  if (failure) std::rethrow_exception(failure);
}

}  // namespace nbar::python
