// nbar export: the links' plates as a DXF drawing for cutting, or as SVG.
#include <optional>

#include "commands.hpp"
#include "common.hpp"
#include "nbar/analysis/pose.hpp"
#include "nbar/io/dxf_writer.hpp"
#include "nbar/kinematics/sweep.hpp"

namespace nbar::cli {

namespace {

struct ExportArgs {
  std::string model, dxf, svg;
  std::optional<double> at;
};

int run_export(const ExportArgs& args) {
  if (args.dxf.empty() && args.svg.empty()) {
    std::cerr << "error: nbar export needs --dxf FILE.dxf or --svg FILE.svg (or both)\n";
    return kBadUsage;
  }
  Loaded loaded;
  if (int code = load(args.model, loaded)) return code;
  const Mechanism& mech = *loaded.mechanism;
  try {
    // Without --at, the plates lie as drawn in the model file.
    std::vector<Eigen::Vector2d> points;
    for (const Point& p : mech.model().points) points.push_back(p.position);
    if (args.at) points = point_positions(mech, pose_at(mech, *args.at).taylor.col(0));
    if (!args.dxf.empty() && !write_file(args.dxf, io::cutting_dxf(mech, points))) return kBadUsage;
    if (!args.svg.empty() && !write_file(args.svg, io::cutting_svg(mech, points))) return kBadUsage;
  } catch (const Error& e) {
    return fail(args.model, e);
  }
  return kOk;
}

}  // namespace

Command add_export_command(CLI::App& app) {
  auto args = std::make_shared<ExportArgs>();
  CLI::App* sub = app.add_subcommand("export",
                                     "Write the links' plates (outlines, arcs, holes) as a DXF drawing for "
                                     "cutting, one layer per link, or as SVG");
  sub->add_option("MODEL", args->model, "model file (YAML or JSON)")->required();
  sub->add_option("--dxf", args->dxf, "FILE.dxf: AutoCAD R12 ASCII DXF, in the model's length unit");
  sub->add_option("--svg", args->svg, "FILE.svg: the same plates as SVG, one group per link, true size in mm");
  sub->add_option("--at", args->at,
                  "place the plates where the first driver has this value (model units; a time for time laws); "
                  "default: as drawn in the model file");
  return {sub, [args] { return run_export(*args); }};
}

}  // namespace nbar::cli
