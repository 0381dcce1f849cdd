// The bundled examples (examples/*.yaml) as the tests load them, defined once for all test files:
// a test program compiles its files in unity batches, where a file-private copy would be defined
// twice.
#pragma once

#include "nbar/io/model_file.hpp"
#include "nbar/kinematics/mechanism.hpp"
#include "nbar/model/model.hpp"

#include <filesystem>
#include <memory>
#include <string>

namespace nbar::test_support {

// examples/<file_name>, read as `nbar` reads it; a file that fails throws its located nbar::Error.
inline Model example_model(const std::string& file_name) {
  return io::load_model_file((std::filesystem::path(NBAR_EXAMPLES_DIR) / file_name).string()).model;
}

inline std::shared_ptr<const Mechanism> example_mechanism(const std::string& file_name) {
  return std::make_shared<const Mechanism>(example_model(file_name));
}

}  // namespace nbar::test_support
