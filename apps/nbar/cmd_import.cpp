// nbar import: a model skeleton from a sketch of several links (DXF, SVG or sketch CSV).
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>

#include "commands.hpp"
#include "common.hpp"
#include "nbar/io/file_text.hpp"
#include "nbar/io/sketch.hpp"
#include "nbar/io/sketch_model.hpp"
#include "nbar/model/materials.hpp"
#include "nbar/model/units.hpp"
#include "validators.hpp"

namespace nbar::cli {

namespace {

struct ImportArgs {
  std::string sketch, output, units, material = "steel";
  std::optional<double> thickness;
};

// The name of a length unit nbar knows of `metres` per unit, if any.
std::optional<std::string> unit_name(double metres) {
  for (const char* unit : {"mm", "cm", "m", "in", "ft"}) {
    if (std::abs(*length_unit_scale(unit) - metres) <= 1e-12 * metres) return std::string(unit);
  }
  return std::nullopt;
}

int run_import(const ImportArgs& args) {
  const std::optional<io::SketchFormat> format = io::sketch_format(args.sketch);
  if (!format) {
    std::cerr << "error: nbar import reads DXF (.dxf), SVG (.svg) or sketch CSV (.csv, .txt) files, not " << args.sketch
              << '\n';
    return kBadUsage;
  }
  if (!args.units.empty() && !length_unit_scale(args.units)) {
    std::cerr << "error: --units is one of mm, cm, m, in, ft, not '" << args.units << "'\n";
    return kBadUsage;
  }
  const io::FileText file = io::read_file_text(args.sketch);
  if (file.error || file.too_long) {
    std::cerr << "error: cannot read " << args.sketch << ": "
              << (file.error ? file.error.message() : io::too_long_message()) << '\n';
    return kBadUsage;
  }
  try {
    const io::Sketch sketch = io::read_sketch(file.text, args.sketch, *format);
    io::SketchModelOptions options;
    options.source_name = args.sketch;
    // The model's unit: --units, else the sketch's own, else mm; a sketch without a unit is
    // taken in the model's.
    options.length_unit = !args.units.empty() ? args.units
                          : sketch.metres_per_unit && unit_name(*sketch.metres_per_unit)
                              ? *unit_name(*sketch.metres_per_unit)
                              : std::string("mm");
    options.scale = io::sketch_scale(sketch, std::nullopt, *length_unit_scale(options.length_unit));
    // 5 mm unless given, in the model's unit.
    options.thickness = args.thickness ? *args.thickness : 5e-3 / *length_unit_scale(options.length_unit);
    options.material = args.material;
    // A material of the user's own is allowed (defined under `materials:` later), but say so: the
    // model written names a material it does not define, and `nbar check` refuses it until then.
    if (!builtin_material(args.material))
      std::cerr << "warning: '" << args.material << "' is not a built-in material (" << join(builtin_material_names())
                << "): define it under `materials:` in the model written\n";
    const std::string yaml = io::model_from_sketch(sketch, options);
    if (args.output.empty()) {
      Output output;
      output.open("");
      output.stream() << yaml;
      if (!output.finish()) return kBadUsage;
    } else if (!write_file(args.output, yaml)) {
      return kBadUsage;
    }
  } catch (const Error& e) {
    return fail(args.sketch, e);
  }
  return kOk;
}

}  // namespace

Command add_import_command(CommandLine& app) {
  auto args = std::make_shared<ImportArgs>();
  Subcommand* sub = app.add_subcommand("import",
                                       "A model skeleton from a sketch of several links (DXF, SVG or sketch "
                                       "CSV): outlines become bodies, coinciding pin holes joints");
  sub->add_option("SKETCH", args->sketch, "FILE.dxf, FILE.svg or FILE.csv")->required();
  sub->add_option("-o,--output", args->output, "the model file to write (default: standard output)")
      ->check(nbar::cli::output_file());
  sub->add_option("--units", args->units,
                  "the model's length unit (mm, cm, m, in, ft; default: the sketch's own, else mm); a sketch that "
                  "states no unit is read in it");
  sub->add_option("--thickness", args->thickness, "every plate's thickness in the model's unit (default: 5 mm)")
      ->check(nbar::cli::positive());
  sub->add_option("--material", args->material, "every plate's material (default steel)");
  return {sub, [args] { return run_import(*args); }};
}

}  // namespace nbar::cli
