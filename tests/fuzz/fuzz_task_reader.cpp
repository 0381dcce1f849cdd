// libFuzzer harness: the synthesis task reader (docs/synthesis.md). Any input must end in a task
// or in a located ModelFileError.
#include <cstddef>
#include <cstdint>
#include <string>

#include "nbar/io/synthesis_task.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)nbar::io::parse_synthesis_task(text, "fuzz-task.yaml");
  } catch (const nbar::io::ModelFileError&) {
  }
  return 0;
}
