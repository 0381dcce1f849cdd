// A first guess the model editor offers (the web app's body panel), kept in the core so that
// every front-end offers the same.
#pragma once

#include "nbar/model/model.hpp"

namespace nbar {

// The width a new `bar:` of `model.bodies[body]` starts from, in the model's length unit (as a
// person writes it in the model file): a tenth of the drawn distance from its first point to its
// second, to two significant digits (18 for 179.9999998 mm), or 1 when that distance is zero or
// the body has fewer than two points. The web app's body panel offers it.
double default_bar_width(const Model& model, int body);

}  // namespace nbar
