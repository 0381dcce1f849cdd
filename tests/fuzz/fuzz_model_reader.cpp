// libFuzzer harness: the model reader (YAML/JSON text -> Model). Any input must end in a Model or
// in a located ModelFileError; anything else (another exception, a crash, a sanitizer report, a
// timeout, more memory than -rss_limit_mb) is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "nbar/io/model_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)nbar::io::parse_model(text, "fuzz.yaml");
  } catch (const nbar::io::ModelFileError&) {
  }
  return 0;
}
