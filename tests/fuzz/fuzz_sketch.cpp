// libFuzzer harness: the sketch readers (DXF, SVG, sketch CSV: `shape: {import}` and
// `nbar import`). The first byte picks the format, the rest is the file. Reading may only throw
// ModelFileError; a sketch read becomes a plate whose loops have finite areas, and a model
// skeleton (which may only throw Error).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "nbar/io/model_file.hpp"
#include "nbar/io/sketch.hpp"
#include "nbar/io/sketch_model.hpp"
#include "nbar/model/diagnostics.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const nbar::io::SketchFormat formats[] = {nbar::io::SketchFormat::kDxf, nbar::io::SketchFormat::kSvg,
                                            nbar::io::SketchFormat::kCsv};
  const nbar::io::SketchFormat format = formats[data[0] % 3];
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  nbar::io::Sketch sketch;
  try {
    sketch = nbar::io::read_sketch(text, "fuzz", format);
  } catch (const nbar::io::ModelFileError&) {
    return 0;
  }
  for (const nbar::io::SketchLoop& loop : sketch.loops) {
    if (!std::isfinite(loop.area())) std::abort();
  }
  nbar::io::plate_from_sketch(sketch, 1.0);
  try {
    nbar::io::model_from_sketch(sketch, {"fuzz", "mm", 1.0, 5.0, "steel"});
  } catch (const nbar::Error&) {
  }
  return 0;
}
