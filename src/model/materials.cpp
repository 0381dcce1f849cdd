#include "nbar/model/materials.hpp"

#include "nbar/model/units.hpp"

#include <string_view>
#include <utility>

namespace nbar {

namespace {

// Name, density (kg/m^3), yield strength (MPa; 0 = none, for brittle materials), Young's
// modulus (GPa) and Poisson's ratio: room-temperature handbook values (ASM Handbook and
// MatWeb data sheets of the grades named; docs/kinetics.md tables them).
struct Entry {
  const char* name;
  double density;
  double yield_mpa;
  double youngs_gpa;
  double poisson;
};
constexpr Entry kMaterials[] = {
    {"steel", 7850, 250, 200, 0.30},            // structural steel, S235 / A36
    {"stainless-steel", 8000, 215, 193, 0.29},  // austenitic, 304
    {"aluminium", 2700, 276, 68.9, 0.33},       // 6061-T6
    {"brass", 8500, 200, 97, 0.31},             // free-cutting brass, C36000
    {"cast-iron", 7200, 0, 100, 0.26},          // grey iron (class 30): brittle, no yield point
    {"titanium", 4430, 880, 113.8, 0.34},       // Ti-6Al-4V
    {"abs", 1050, 40, 2.3, 0.35},               // moulded ABS
    {"acrylic", 1180, 70, 3.2, 0.37},           // PMMA
    {"nylon", 1150, 70, 2.8, 0.39},             // PA6 / PA66, dry
};
constexpr double kPascalPerGigapascal = 1e9;

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
      m.youngs_modulus = e.youngs_gpa * kPascalPerGigapascal;
      m.poisson_ratio = e.poisson;
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
