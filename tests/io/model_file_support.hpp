// Shared by the model-file tests: does parsing fail at the right place with the right words?
#pragma once

#include <gtest/gtest.h>

#include <exception>
#include <string>

#include "nbar/io/model_file.hpp"

namespace nbar::io::test_support {

// Checks that parsing `text` (as "m.yaml") fails at exactly `location` ("line:column") with
// a message containing `phrase`.
inline ::testing::AssertionResult fails_at(const std::string& text, const std::string& location,
                                           const std::string& phrase) {
  try {
    parse_model(text, "m.yaml");
  } catch (const ModelFileError& e) {
    const std::string what = e.what();
    std::string prefix = "m.yaml:";
    prefix.append(location).append(": ");
    if (what.rfind(prefix, 0) != 0) return ::testing::AssertionFailure() << "error at the wrong place: " << what;
    if (what.find(phrase) == std::string::npos) {
      return ::testing::AssertionFailure() << "message lacks '" << phrase << "': " << what;
    }
    if (prefix + e.message() != what) return ::testing::AssertionFailure() << "message() differs from what(): " << what;
    return ::testing::AssertionSuccess();
  } catch (const std::exception& e) {
    return ::testing::AssertionFailure() << "not a ModelFileError: " << e.what();
  }
  return ::testing::AssertionFailure() << "parsed without error";
}

}  // namespace nbar::io::test_support
