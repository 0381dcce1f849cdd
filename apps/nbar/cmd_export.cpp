// nbar export: the links' plates as a DXF drawing for cutting.
#include <optional>

#include "commands.hpp"
#include "common.hpp"
#include "nbar/analysis/pose.hpp"
#include "nbar/io/dxf_writer.hpp"
#include "nbar/kinematics/sweep.hpp"

namespace nbar::cli {

namespace {

struct ExportArgs {
  std::string model, dxf;
  std::optional<double> at;
};

int run_export(const ExportArgs& args) {
  Loaded loaded;
  if (int code = load(args.model, loaded)) return code;
  const Mechanism& mech = *loaded.mechanism;
  try {
    // Without --at, the plates lie as drawn in the model file.
    std::vector<Eigen::Vector2d> points;
    for (const Point& p : mech.model().points) points.push_back(p.position);
    if (args.at) points = point_positions(mech, pose_at(mech, *args.at).taylor.col(0));
    if (!write_file(args.dxf, io::cutting_dxf(mech, points))) return kBadUsage;
  } catch (const Error& e) {
    return fail(args.model, e);
  }
  return kOk;
}

}  // namespace

Command add_export_command(CLI::App& app) {
  auto args = std::make_shared<ExportArgs>();
  CLI::App* sub = app.add_subcommand("export", "Write the links' plates (outlines, arcs, holes) as a DXF drawing for "
                                               "cutting, one layer per link");
  sub->add_option("MODEL", args->model, "model file (YAML or JSON)")->required();
  sub->add_option("--dxf", args->dxf, "FILE.dxf: AutoCAD R12 ASCII DXF, in the model's length unit")->required();
  sub->add_option("--at", args->at,
                  "place the plates where the first driver has this value (model units; a time for time laws); "
                  "default: as drawn in the model file");
  return {sub, [args] { return run_export(*args); }};
}

}  // namespace nbar::cli
