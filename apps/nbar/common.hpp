// Shared by the nbar commands: loading a model, running its sweep, writing to a file or
// standard output, and the documented exit codes.
#pragma once

#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "nbar/io/model_file.hpp"
#include "nbar/kinematics/sweep.hpp"

namespace nbar::cli {

enum ExitCode { kOk = 0, kInvalidModel = 1, kBadUsage = 2, kCannotAssemble = 3, kStoppedEarly = 4 };

using nbar::io::LoadedModel;

// Loads and compiles a model, reporting every problem at its place in the file.
struct Loaded {
  LoadedModel file;
  std::optional<nbar::Mechanism> mechanism;
};

inline int load(const std::string& path, Loaded& out) {
  try {
    out.file = nbar::io::load_model_file(path);
  } catch (const nbar::io::ModelFileError& e) {
    std::cerr << "error: " << e.what() << '\n';
    return kInvalidModel;
  }
  try {
    out.mechanism.emplace(out.file.model);
  } catch (const nbar::ModelError& e) {
    std::cerr << "error: " << nbar::io::locate(out.file.source, e) << '\n';
    return kInvalidModel;
  }
  return kOk;
}

inline std::string join(const std::vector<std::string>& items, const std::string& sep = ", ") {
  std::string s;
  for (std::size_t i = 0; i < items.size(); ++i) s += (i ? sep : "") + items[i];
  return s;
}

// Warnings, and the exit code of a sweep that stopped early.
inline int finish(const std::string& model, const nbar::SweepResult& sweep) {
  if (!sweep.complete) {
    std::cerr << "error: " << model << ": " << sweep.stop_reason << " (" << sweep.samples.size()
              << " rows written)\n";
    return kStoppedEarly;
  }
  return kOk;
}

// Runs the sweep; the exit code says what went wrong (0 when it ran, even if it stopped early).
inline int sweep_model(const std::string& path, const nbar::Mechanism& mech, const nbar::SweepOptions& options,
                nbar::SweepResult& sweep) {
  try {
    sweep = nbar::run_sweep(mech, options);
  } catch (const nbar::AssemblyError& e) {
    std::cerr << "error: " << path << ": " << e.what() << '\n';
    return kCannotAssemble;
  } catch (const std::invalid_argument& e) {
    std::cerr << "error: " << e.what() << '\n';
    return kBadUsage;
  } catch (const std::domain_error& e) {  // a driver's law undefined at the start
    std::cerr << "error: " << path << ": " << e.what() << '\n';
    return kCannotAssemble;
  }
  return kOk;
}

// Standard output, or the file named by -o.
class Output {
 public:
  // False, with a message, when the file cannot be written.
  bool open(const std::string& path) {
    if (path.empty()) return true;
    file_.open(path);
    if (!file_) std::cerr << "error: cannot write " << path << '\n';
    return static_cast<bool>(file_);
  }
  std::ostream& stream() { return file_.is_open() ? file_ : std::cout; }

 private:
  std::ofstream file_;
};


}  // namespace nbar::cli
