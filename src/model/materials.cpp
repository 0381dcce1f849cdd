#include "nbar/model/materials.hpp"

#include "nbar/model/units.hpp"

#include <string_view>
#include <utility>

namespace nbar {

namespace {

// Name, density (kg/m^3), yield strength (MPa; 0 = none, for brittle materials).
struct Entry {
  const char* name;
  double density;
  double yield_mpa;
};
constexpr Entry kMaterials[] = {
    {"steel", 7850, 250},            // structural steel, S235 / A36
    {"stainless-steel", 8000, 215},  // austenitic, 304
    {"aluminium", 2700, 276},        // 6061-T6
    {"brass", 8500, 200},            // free-cutting brass
    {"cast-iron", 7200, 0},          // grey iron: brittle, no yield point
    {"titanium", 4430, 880},         // Ti-6Al-4V
    {"abs", 1050, 40},               // moulded ABS
    {"acrylic", 1180, 70},           // PMMA
    {"nylon", 1150, 70},             // PA6 / PA66, dry
};

constexpr std::pair<const char*, const char*> kAliases[] = {
    {"aluminum", "aluminium"},
};

}  // namespace

const std::vector<Material>& builtin_materials() {
  static const std::vector<Material> materials = [] {
    std::vector<Material> out;
    for (const Entry& e : kMaterials) {
      Material m;
      m.name = e.name;
      m.density = e.density;
      if (e.yield_mpa > 0) m.yield_strength = e.yield_mpa * kPascalPerMegapascal;
      out.push_back(std::move(m));
    }
    return out;
  }();
  return materials;
}

std::vector<std::string> builtin_material_names() {
  std::vector<std::string> names;
  for (const Entry& e : kMaterials) names.emplace_back(e.name);
  for (const auto& alias : kAliases) names.emplace_back(alias.first);
  return names;
}

std::optional<Material> builtin_material(const std::string& name) {
  std::string_view canonical = name;
  for (const auto& alias : kAliases) {
    if (name == alias.first) canonical = alias.second;
  }
  for (const Material& m : builtin_materials()) {
    if (m.name == canonical) return m;
  }
  return std::nullopt;
}

}  // namespace nbar
