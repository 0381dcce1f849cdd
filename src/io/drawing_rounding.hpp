// Internal to the writers of drawings and of models from drawings (sketch_model.cpp, which
// imports, and dxf_writer.cpp, which exports DXF and SVG outlines): the rounding of the
// coordinates they write, relative to the drawing's size.
#pragma once

#include <cmath>
#include <cstdlib>
#include <string>

namespace nbar::io::drawing_detail {

// Coordinates written are rounded to a power of ten of about 1e-12 of the drawing's size
// (10^(ceil(log10 size) - 12)), so that rounding noise (29.999999999999996, 2.5e-16) is written
// 30 and 0. The step is relative, not a fixed 1e-9 of the unit: that one left a drawing in
// metres 3 or 4 significant digits at 1e-6 and wrote one 1e-15 the size as all zeros, whose
// outlines then had coinciding vertices. For drawings from 100 to 1000 units across (a part in
// mm) the step is 1e-9 as it was, so their text is written as before, bit for bit.
class Tidy {
 public:
  explicit Tidy(double size) {
    if (!(size > 0) || !std::isfinite(size)) return;  // no extent to be relative to: as it is
    const int exponent = static_cast<int>(std::ceil(std::log10(size))) - 12;
    // 10^|exponent| read as the literal is, correctly rounded; the step 1e-9 is then
    // round(v * 1e9) / 1e9, the arithmetic it always was, bit for bit.
    power_ = std::strtod(("1e" + std::to_string(std::abs(exponent))).c_str(), nullptr);
    fine_ = exponent < 0;
    if (!std::isfinite(power_)) power_ = 0;  // a size times a scale beyond double's range
  }
  double operator()(double v) const {
    if (power_ == 0) return v;
    const double t = fine_ ? std::round(v * power_) / power_ : std::round(v / power_) * power_;
    if (!std::isfinite(t)) return v;  // a stray circle far beyond the outlines, say
    return t == 0.0 ? 0.0 : t;        // no "-0"
  }

 private:
  double power_ = 0;  // 10^|exponent|, 0 when there is no rounding
  bool fine_ = true;  // the step is 1 / power_ (else power_)
};

}  // namespace nbar::io::drawing_detail
