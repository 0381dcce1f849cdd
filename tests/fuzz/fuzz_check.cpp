// libFuzzer harness: the whole path of `nbar check`: read the model, compile the Mechanism
// (validation, mobility, loops) and summarise it (assembly at the start). Every error must be an
// nbar::Error; a summary's numbers must be finite. The limit search gets a fiftieth of its default
// work budget: this build (-O1, ASan, UBSan, coverage) runs Eigen's dense factorisations some 35
// times slower than Release, and the per-input time limit is 10 s; the budget's own path, the
// search stopping and saying so, is what a slow input exercises.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <string>

#include "nbar/analysis/summary.hpp"
#include "nbar/io/model_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const nbar::io::LoadedModel loaded = nbar::io::parse_model(text, "fuzz.yaml");
    const auto mechanism = std::make_shared<const nbar::Mechanism>(loaded.model);
    const nbar::ModelSummary summary =
        nbar::summarize(*mechanism, nbar::kDefaultMaxSweepSamples, 0.02 * nbar::kDefaultLimitSearchWork);
    (void)summary;
  } catch (const nbar::Error&) {
  }
  return 0;
}
