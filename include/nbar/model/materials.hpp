// Built-in materials, usable by name in model files (`material: steel`).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "nbar/model/model.hpp"

namespace nbar {

// The built-in materials in a fixed order (for documentation and error messages), each
// under its canonical name. Typical values for a first design, not for certification.
const std::vector<Material>& builtin_materials();

// Every name builtin_material() accepts: the canonical names, then aliases ("aluminum").
std::vector<std::string> builtin_material_names();

// The built-in material of that name or alias (exact, case-sensitive); the returned
// material carries the canonical name.
std::optional<Material> builtin_material(const std::string& name);

}  // namespace nbar
