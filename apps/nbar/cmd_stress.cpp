// nbar stress: every shaped link's largest stress, or one link's sections at one step.
#include <filesystem>
#include <fstream>
#include <iostream>

#include "commands.hpp"
#include "common.hpp"
#include "nbar/io/fe_export.hpp"
#include "nbar/request/requests.hpp"
#include "request_flags.hpp"
#include "validators.hpp"

namespace nbar::cli {

namespace {

struct StressCommand {
  std::string model;
  std::string output;
  std::unique_ptr<RequestFlags> flags;
};

// Each mesh the request asks for, as three files in its directory.
int export_meshes(const request::StressRequest& request, const Analysis& analysis) {
  std::vector<request::StressRequest::MeshExport> meshes;
  try {
    meshes = request.mesh_exports(analysis);
  } catch (const request::OptionError& e) {
    print_option_error(e);
    return kBadUsage;
  }
  if (meshes.empty()) return 0;
  const std::filesystem::path directory(request.export_mesh);
  std::error_code made;
  std::filesystem::create_directories(directory, made);
  for (const auto& mesh : meshes) {
    const auto write = [&](const std::string& name, const auto& writer) {
      std::ofstream file(directory / name);
      writer(file);
      return static_cast<bool>(file);
    };
    const bool written =
        write(mesh.stem + ".vtu", [&](std::ostream& o) { io::write_fe_vtu(o, analysis, mesh.body, mesh.step); }) &&
        write(mesh.stem + "-nodes.csv",
              [&](std::ostream& o) { io::write_fe_nodes_csv(o, analysis, mesh.body, mesh.step); }) &&
        write(mesh.stem + "-elements.csv", [&](std::ostream& o) { io::write_fe_elements_csv(o, analysis, mesh.body); });
    if (!written) {
      std::cerr << "error: cannot write " << (directory / mesh.stem).string() << ".* (--export-mesh)\n";
      return kBadUsage;
    }
  }
  return 0;
}

int run_stress(const StressCommand& command) {
  request::StressRequest request;
  if (!read_request(*command.flags, request)) return kBadUsage;
  Loaded loaded;
  if (int code = load(command.model, loaded)) return code;
  Analysis analysis;
  if (int code = analyse_model(command.model, loaded, request.analysis_options(loaded.mechanism->model()), analysis))
    return code;
  ResultTable profile;
  if (request.profile_asked()) {
    try {
      profile = request.section_profile_table(analysis);
    } catch (const request::OptionError& e) {
      print_option_error(e);
      return kBadUsage;
    }
  }
  if (int code = export_meshes(request, analysis)) return code;
  FeConvergence convergence;
  if (request.converge) {
    try {
      convergence = request.convergence(analysis);
    } catch (const Error& e) {
      return fail(command.model, nbar::io::located(loaded.file.source, e));
    }
  }
  Output output;
  if (!output.open(command.output)) return kBadUsage;
  if (request.format == "json") output.json_answer();
  if (request.converge)
    io::write_fe_convergence(output.stream(), request.format, analysis, convergence);
  else if (request.profile_asked())
    io::write_table(output.stream(), request.format, analysis, profile);
  else
    io::write_stress_report(output.stream(), request.format, analysis);
  if (!output.finish()) return kBadUsage;
  return finish(loaded, analysis.sweep);
}

}  // namespace

Command add_stress_command(CommandLine& app) {
  auto command = std::make_shared<StressCommand>();
  Subcommand* sub = app.add_subcommand("stress",
                                       "Stresses in every link that has a shape: the largest von Mises "
                                       "stress over the sweep, where and when, and the safety factor");
  sub->add_option("MODEL", command->model, "model file (YAML or JSON)")->required();
  command->flags = std::make_unique<RequestFlags>(*sub, request::StressRequest::rules());
  command->flags->add({"steps", "max_steps", "method", "sections", "mesh_size", "format"});
  sub->add_option("-o,--output", command->output, "write to FILE instead of standard output")
      ->check(nbar::cli::output_file());
  command->flags->add({"section_profile", "step"});
  command->flags->add({"at", "along", "around_hole", "coordinates", "radius", "samples", "export_mesh"});
  command->flags->add({"segments_per_hole", "edge_size", "converge", "tolerance"});
  return {sub, [command] { return run_stress(*command); }};
}

}  // namespace nbar::cli
