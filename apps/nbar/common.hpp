// Shared by the nbar commands: loading a model, mapping the library's errors to messages and
// the documented exit codes, printing warnings, writing to a file or standard output.
#pragma once

#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "nbar/analysis/analysis.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/io/results_writer.hpp"
#include "nbar/model/file_errors.hpp"
#include "language.hpp"

namespace nbar::cli {

enum ExitCode { kOk = 0, kInvalidModel = 1, kBadUsage = 2, kCannotAssemble = 3, kStoppedEarly = 4, kCancelled = 5 };

// The one place where kinds of error become exit codes.
inline int exit_code(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::InvalidModel: return kInvalidModel;
    case ErrorKind::UndefinedLaw: return kInvalidModel;  // the model's law is wrong where it is used
    case ErrorKind::BadInput: return kBadUsage;
    case ErrorKind::CannotAssemble: return kCannotAssemble;
    case ErrorKind::StoppedAtLimit: return kStoppedEarly;
    case ErrorKind::Cancelled: return kCancelled;
    case ErrorKind::Internal: return kBadUsage;
  }
  return kBadUsage;
}

// The error's whole text with its message in the language asked: its place ("file:line:column: ",
// an option's name) is kept as it is, only the message after it is said again.
inline std::string said(const Error& e) {
  std::string text = e.what();
  const std::string& message = e.message();
  if (!message.empty() && text.size() >= message.size() && text.ends_with(message))
    return text.substr(0, text.size() - message.size()) + say(message);
  return say(text);
}

// Prints the error, prefixed by the model file's name when the error does not carry a place
// of its own, and returns its exit code. Bad input is about the options, an internal error
// about nbar or the system, neither about the file.
inline int fail(const std::string& model_path, const Error& e) {
  if (!e.file().empty() || e.kind() == ErrorKind::BadInput || e.kind() == ErrorKind::Internal || model_path.empty())
    std::cerr << "error: " << said(e) << '\n';
  else
    std::cerr << "error: " << model_path << ": " << say(e.message()) << '\n';
  return exit_code(e.kind());
}

// The text after a path's last dot ("svg" for "gear.svg"), which picks a picture's format.
inline std::string extension(const std::string& path) {
  const auto dot = path.rfind('.');
  return dot == std::string::npos ? "" : path.substr(dot + 1);
}

// A model file, compiled; errors are reported at their place in the file.
struct Loaded {
  nbar::io::LoadedModel file;
  std::shared_ptr<const Mechanism> mechanism;
};

inline int load(const std::string& path, Loaded& out) {
  try {
    out.file = nbar::io::load_model_file(path);
    try {
      out.mechanism = std::make_shared<const Mechanism>(out.file.model);
    } catch (const ModelError& e) {
      throw nbar::io::ModelFileError(path, out.file.source.find(e.where()), e.message());
    }
  } catch (const Error& e) {
    return fail(path, e);
  }
  return kOk;
}

inline std::string join(const std::vector<std::string>& items, const std::string& sep = ", ") {
  std::string s;
  for (std::size_t i = 0; i < items.size(); ++i) s += (i ? sep : "") + items[i];
  return s;
}

inline void print_warnings(const std::vector<Warning>& warnings) {
  for (const Warning& w : warnings) std::cerr << "warning: " << say(w.message) << '\n';
}

// A rocking sweep's turns, one line each, where warnings go.
inline void print_reversals(const Model& m, const SweepResult& sweep) {
  for (const Reversal& r : sweep.reversals)
    std::cerr << "reversed: "
              << (r.at_sample
                      ? "at step " + std::to_string(r.after_step)
                      : "between steps " + std::to_string(r.after_step) + " and " + std::to_string(r.after_step + 1))
              << ", at t = " << r.time << " s, " << m.drivers[0].name << " = "
              << format_driver_value(m, 0, r.driver_value) << " (" << r.involved << ")\n";
}

// The exit code of a sweep that stopped early (its rows are written), or 0.
inline int finish(const Loaded& loaded, const SweepResult& sweep) {
  print_reversals(loaded.file.model, sweep);
  if (!sweep.complete) {
    const nbar::io::SourceMap& source = loaded.file.source;
    std::cerr << "error: " << compose_location(source.file, source.sweep_stop(), say(sweep.stop_reason)) << ' '
              << say("(" + std::to_string(sweep.solved) + " rows written)") << '\n';
    return kStoppedEarly;
  }
  return kOk;
}

// Runs the analysis; the exit code says what went wrong (0 when it ran, even if the sweep
// stopped early).
inline int analyse_model(const std::string& path, const Loaded& loaded, const AnalysisOptions& options, Analysis& out) {
  try {
    out = analyse(loaded.mechanism, options);
  } catch (const Error& e) {
    return fail(path, nbar::io::located(loaded.file.source, e));
  }
  return kOk;
}

// Writes a picture's or a document's bytes to `path`; false, after saying why, when it cannot.
inline bool write_file(const std::string& path, const char* data, std::size_t size) {
  std::ofstream out(path, std::ios::binary);
  // Closed before it is judged: a full disk fails the flush, after write() has taken the bytes.
  if (out.write(data, static_cast<std::streamsize>(size))) out.close();
  if (out) return true;
  std::cerr << "error: " << cannot_write_message(path) << '\n';
  return false;
}
inline bool write_file(const std::string& path, const std::string& text) {
  return write_file(path, text.data(), text.size());
}
inline bool write_file(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  return write_file(path, reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

// The width a text table is wrapped to: $COLUMNS when it is a sensible number, else 80
// (io::kTextTableWidth, as the web API).
inline std::size_t terminal_width() {
  const char* columns = std::getenv("COLUMNS");
  const long value = columns ? std::strtol(columns, nullptr, 10) : 0;
  return value >= 20 && value <= 10000 ? static_cast<std::size_t>(value) : io::kTextTableWidth;
}

// Standard output, or the file named by -o.
class Output {
 public:
  // False, with a message, when the file cannot be written.
  bool open(const std::string& path) {
    path_ = path;
    if (path.empty()) return true;
    file_.open(path);
    if (!file_) std::cerr << "error: " << cannot_write_message(path) << '\n';
    return static_cast<bool>(file_);
  }
  std::ostream& stream() {
    if (json_) return json_answer_;
    return file_.is_open() ? file_ : std::cout;
  }

  // What is written is a JSON answer: its message fields are said in the language asked (as the
  // web API says them) when it is finished. In English it is written as it comes.
  void json_answer() { json_ = spoken_language() != request::Language::English; }

  // Flushes (and closes the file): false, with a message, when what was written did not all get
  // there (a full disk, a closed pipe), which the writes themselves need not show.
  bool finish() {
    if (json_) {
      json_ = false;
      stream() << say_json(json_answer_.str());
    }
    stream().flush();
    if (file_.is_open()) file_.close();  // a failed close sets the file's failbit
    if (path_.empty() ? static_cast<bool>(std::cout) : static_cast<bool>(file_)) return true;
    std::cerr << "error: "
              << (path_.empty() ? "cannot write to standard output" + reason() : cannot_write_message(path_)) << '\n';
    return false;
  }

 private:
  static std::string reason() { return errno != 0 ? std::string(": ") + std::strerror(errno) : std::string(); }

  std::string path_;
  std::ofstream file_;
  bool json_ = false;
  std::ostringstream json_answer_;
};

}  // namespace nbar::cli
