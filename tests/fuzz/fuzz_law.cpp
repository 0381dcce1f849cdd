// libFuzzer harness: the law (expression) parser and its evaluation as a number and as a Taylor
// series. Parsing may only throw LawSyntaxError; evaluating may only throw Error(UndefinedLaw),
// and what it returns must be finite.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "nbar/model/law.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  nbar::Law law;
  try {
    law = nbar::Law::parse(text);
  } catch (const nbar::LawSyntaxError&) {
    return 0;
  }
  for (const double t : {0.0, 0.5, 1.0, -2.0, 1e6}) {
    try {
      if (!std::isfinite(law.value(t))) std::abort();
    } catch (const nbar::Error& e) {
      if (e.kind() != nbar::ErrorKind::UndefinedLaw) std::abort();
    }
    try {
      const nbar::Series s = law.series(t, 6);
      for (int k = 0; k < s.terms(); ++k)
        if (!std::isfinite(s[k])) std::abort();
    } catch (const nbar::Error& e) {
      if (e.kind() != nbar::ErrorKind::UndefinedLaw) std::abort();
    }
  }
  return 0;
}
