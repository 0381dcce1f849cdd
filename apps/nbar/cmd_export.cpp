// nbar export: the links' plates as a DXF drawing for cutting, or as SVG.
#include "commands.hpp"
#include "common.hpp"
#include "nbar/request/requests.hpp"
#include "request_flags.hpp"

namespace nbar::cli {

namespace {

struct ExportCommand {
  std::string model, dxf, svg;
  std::unique_ptr<RequestFlags> flags;
};

int run_export(const ExportCommand& command) {
  if (command.dxf.empty() && command.svg.empty()) {
    std::cerr << "error: nbar export needs --dxf FILE.dxf or --svg FILE.svg (or both)\n";
    return kBadUsage;
  }
  request::ExportRequest request;
  if (!read_request(*command.flags, request)) return kBadUsage;
  Loaded loaded;
  if (int code = load(command.model, loaded)) return code;
  const Mechanism& mech = *loaded.mechanism;
  try {
    const std::vector<Eigen::Vector2d> points = request.points(mech);
    // The format comes from the flag naming the file; both may be given.
    for (const auto& [format, file] : {std::pair{"dxf", &command.dxf}, std::pair{"svg", &command.svg}}) {
      if (file->empty()) continue;
      request.format = format;
      if (!write_file(*file, request.plates(mech, points))) return kBadUsage;
    }
  } catch (const Error& e) {
    return fail(command.model, nbar::io::located(loaded.file.source, e));
  }
  return kOk;
}

}  // namespace

Command add_export_command(CommandLine& app) {
  auto command = std::make_shared<ExportCommand>();
  Subcommand* sub = app.add_subcommand("export",
                                       "Write the links' plates (outlines, arcs, holes) as a DXF drawing for "
                                       "cutting, one layer per link, or as SVG");
  sub->add_option("MODEL", command->model, "model file (YAML or JSON)")->required();
  sub->add_option("--dxf", command->dxf, "FILE.dxf: AutoCAD R12 ASCII DXF, in the model's length unit");
  sub->add_option("--svg", command->svg, "FILE.svg: the same plates as SVG, one group per link, true size in mm");
  command->flags = std::make_unique<RequestFlags>(*sub, request::ExportRequest::rules());
  command->flags->add({"at"});
  return {sub, [command] { return run_export(*command); }};
}

}  // namespace nbar::cli
