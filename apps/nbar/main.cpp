// nbar: the command-line front-end. It only translates between the terminal and the core.
//
// Exit codes: 0 success; 1 invalid model; 2 bad usage; 3 cannot assemble at the start;
// 4 sweep stopped early (the rows solved so far are written).
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>

#include "nbar/dynamics/dynamics_table.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/io/results_writer.hpp"
#include "nbar/kinematics/sweep.hpp"
#include "nbar/kinematics/table.hpp"
#include "nbar/stress/link_stress.hpp"

namespace {

using namespace nbar::cli;

std::string length_text(const nbar::Model& m, double si) { return fmt::format("{:.6g} {}", si / m.units.length_scale, m.units.length); }

std::string describe_driver(const nbar::Model& m, int d) {
  const nbar::Driver& drv = m.drivers[d];
  std::string what;
  switch (drv.kind) {
    case nbar::DriverKind::Angle:
      what = "angle of " + m.bodies[drv.body].name +
             (drv.relative_to < 0 ? std::string(" (from +x)") : " relative to " + m.bodies[drv.relative_to].name);
      break;
    case nbar::DriverKind::Distance:
      what = "distance " + m.points[drv.points[0]].name + "-" + m.points[drv.points[1]].name;
      break;
    case nbar::DriverKind::Slide:
      what = "slide of " + m.bodies[m.sliders[drv.slider].body].name + " along its guide";
      break;
  }
  const double rate_scale = drv.is_angular() ? m.units.angle_scale : m.units.length_scale;
  const std::string unit = drv.is_angular() ? m.units.angle : m.units.length;
  if (drv.law) return fmt::format("{}: {}, law {}(t) = {} {}", drv.name, what, drv.name, drv.law->text(), unit);
  std::string motion;
  if (drv.from) motion += ", " + nbar::format_driver_value(m, d, *drv.from);
  if (drv.to) motion += " to " + nbar::format_driver_value(m, d, *drv.to);
  motion += fmt::format(", speed {:.6g} {}/s", drv.speed / rate_scale, unit);
  if (drv.accel != 0.0) motion += fmt::format(", accel {:.6g} {}/s^2", drv.accel / rate_scale, unit);
  return drv.name + ": " + what + motion;
}

void print_kinetics(std::ostream& out, const nbar::Model& m) {
  bool any_mass = false;
  for (const nbar::Body& b : m.bodies) any_mass = any_mass || b.inertia || b.shape;
  if (!any_mass && m.point_loads.empty() && m.torques.empty() && m.springs.empty() && m.gravity.isZero()) return;
  const double unit = m.units.length_scale;
  out << fmt::format("Mass properties (mass kg, centre of mass in {}, inertia about it kg m^2, plate area {}^2):\n",
                     m.units.length, m.units.length);
  for (const nbar::Body& b : m.bodies) {
    const nbar::MassProperties mp = nbar::mass_properties(b);
    std::string source = b.inertia ? "given" : b.shape ? (b.material ? b.material->name : "shape, no material") : "none";
    std::string area = mp.from_shape || b.shape ? fmt::format("  area {:.6g}", mp.area / (unit * unit)) : "";
    out << fmt::format("  {:<12} mass {:.6g}  cg ({:.6g}, {:.6g})  inertia {:.6g}{}  [{}]\n", b.name, mp.mass,
                       mp.cg.x() / unit, mp.cg.y() / unit, mp.inertia, area, source);
  }
  out << fmt::format("Loads: gravity ({:.6g}, {:.6g}) m/s^2, {} point force{}, {} torque{}, {} spring{}\n", m.gravity.x(),
                     m.gravity.y(), m.point_loads.size(), m.point_loads.size() == 1 ? "" : "s", m.torques.size(),
                     m.torques.size() == 1 ? "" : "s", m.springs.size(), m.springs.size() == 1 ? "" : "s");
}

void print_summary(std::ostream& out, const nbar::Mechanism& mech, const std::string& path) {
  const nbar::Model& m = mech.model();
  out << "Model: " << (m.name.empty() ? std::string("(unnamed)") : m.name) << "  [" << path << "]\n";
  out << "Units: length " << m.units.length << ", angle " << m.units.angle << ", time s\n";
  std::vector<std::string> ground, moving;
  for (const nbar::Point& p : m.points) (p.ground ? ground : moving).push_back(p.name);
  out << fmt::format("Points: {} ({} fixed: {}; {} moving: {})\n", m.points.size(), ground.size(), join(ground),
                     moving.size(), join(moving));
  out << "Bodies: " << m.bodies.size() << '\n';
  for (const nbar::Body& b : m.bodies) {
    std::vector<std::string> names;
    for (int p : b.points) names.push_back(m.points[p].name);
    std::string extra;
    if (b.points.size() >= 2) {
      const double len = b.length.value_or((m.points[b.points[1]].position - m.points[b.points[0]].position).norm());
      extra = "  length " + length_text(m, len) + (b.length ? " (given)" : "");
    }
    out << fmt::format("  {:<12} [{}]{}\n", b.name, join(names), extra);
  }
  // Joints: revolute pairs at shared points, then sliders and slots.
  std::vector<std::string> joints;
  for (std::size_t p = 0; p < m.points.size(); ++p) {
    std::vector<std::string> at;
    if (m.points[p].ground) at.push_back("ground");
    for (const nbar::Body& b : m.bodies)
      for (int q : b.points)
        if (q == static_cast<int>(p)) at.push_back(b.name);
    if (at.size() >= 2) joints.push_back("revolute " + m.points[p].name + " (" + join(at, "/") + ")");
  }
  for (const nbar::Slider& s : m.sliders)
    joints.push_back("slider " + m.bodies[s.body].name + " at " + m.points[s.point].name + " along " +
                     m.points[s.along[0]].name + "-" + m.points[s.along[1]].name);
  for (const nbar::Slot& s : m.slots)
    joints.push_back("slot " + m.points[s.point].name + " in " + m.points[s.along[0]].name + "-" + m.points[s.along[1]].name);
  out << "Joints: " << joints.size() << '\n';
  for (const std::string& j : joints) out << "  " << j << '\n';

  const nbar::MobilityReport& mob = mech.mobility();
  out << fmt::format("Degrees of freedom: {} (Gruebler-Kutzbach count {}; {} coordinates, {} constraint equations of rank {})\n",
                     mob.dof, mob.grubler, mob.coordinates, mob.constraint_rows, mob.rank);
  if (mob.grubler != mob.dof)
    out << "  note: the count and the true mobility differ: the linkage has special geometry (redundant constraints)\n";
  if (mob.redundant.empty()) {
    out << "Redundant constraints: none\n";
  } else {
    out << "Redundant constraints: " << mob.redundant.size()
        << " (these depend on the others; the choice among a dependent set is arbitrary)\n";
    for (int r : mob.redundant) out << "  " << mech.rows()[r].label << '\n';
  }
  out << "Drivers: " << m.drivers.size() << '\n';
  for (std::size_t d = 0; d < m.drivers.size(); ++d) out << "  " << describe_driver(m, static_cast<int>(d)) << '\n';
  print_kinetics(out, m);
}

void print_loops(std::ostream& out, const nbar::Mechanism& mech, const nbar::State& state) {
  const auto& loops = mech.four_bar_loops();
  if (loops.empty()) {
    out << "Four-bar loops: none\n";
    return;
  }
  const auto points = nbar::point_positions(mech, state.q);
  const nbar::Model& m = mech.model();
  out << "Four-bar loops: " << loops.size() << '\n';
  for (const nbar::FourBarLoop& loop : loops) {
    const nbar::GrashofReport g = nbar::classify_grashof(loop, points, mech.tolerance());
    out << "  " << loop.name << ": " << nbar::describe(g, loop, m) << '\n';
    out << fmt::format("    at the start: {} branch, transmission angle {:.4g} {}\n",
                       nbar::branch_name(nbar::branch_sign(loop, points)),
                       nbar::transmission_angle(loop, points) / m.units.angle_scale, m.units.angle);
  }
}

int run_check(const std::string& path) {
  Loaded loaded;
  if (int code = load(path, loaded)) return code;
  const nbar::Mechanism& mech = *loaded.mechanism;
  print_summary(std::cout, mech, path);
  nbar::State state(mech);
  try {
    const std::vector<double> start = nbar::sweep_start_values(mech);
    const nbar::AssemblyReport a = nbar::assemble(mech, state, start);
    std::vector<std::string> at;
    for (std::size_t d = 0; d < start.size(); ++d)
      at.push_back(mech.model().drivers[d].name + " = " + nbar::format_driver_value(mech.model(), static_cast<int>(d), start[d]));
    std::cout << fmt::format("Assembly at the start ({}): converged, residual {:.3g} {}\n", join(at),
                             a.residual / mech.model().units.length_scale, mech.model().units.length);
    if (a.passed_singularity)
      std::cout << "  warning: reaching the start from the drawn pose passed a singular position\n";
  } catch (const nbar::AssemblyError& e) {
    std::cout << "Assembly at the start: FAILED\n";
    std::cerr << "error: " << path << ": " << e.what() << '\n';
    return kCannotAssemble;
  } catch (const std::exception& e) {
    std::cerr << "error: " << path << ": " << e.what() << '\n';
    return kCannotAssemble;
  }
  print_loops(std::cout, mech, state);
  return kOk;
}

struct SolveArgs {
  std::string model;
  std::optional<int> steps;
  int order = 2;
  std::string format = "csv";
  std::string output;
  std::vector<std::string> columns;
  bool dynamics = false;
};

int run_solve(const SolveArgs& args) {
  Loaded loaded;
  if (int code = load(args.model, loaded)) return code;
  const nbar::Mechanism& mech = *loaded.mechanism;
  nbar::SweepOptions options;
  options.steps = args.steps;
  options.order = args.dynamics ? std::max(args.order, 2) : args.order;
  nbar::SweepResult sweep;
  if (int code = sweep_model(args.model, mech, options, sweep)) return code;
  nbar::ResultTable table = nbar::make_table(mech, sweep);
  std::optional<nbar::DynamicsSummary> dynamics;
  if (args.dynamics) {
    try {
      dynamics = nbar::append_dynamics(mech, sweep, table);
    } catch (const std::domain_error& e) {  // a load's law undefined at some time
      std::cerr << "error: " << args.model << ": " << e.what() << '\n';
      return kInvalidModel;
    }
  }
  if (!args.columns.empty()) {
    try {
      table = nbar::select_columns(table, args.columns);
    } catch (const std::invalid_argument& e) {
      std::cerr << "error: --columns: " << e.what() << "; the columns are: " << join(nbar::make_table(mech, {}).columns)
                << '\n';
      return kBadUsage;
    }
  }

  Output output;
  if (!output.open(args.output)) return kBadUsage;
  std::ostream& out = output.stream();
  if (args.format == "json")
    nbar::io::write_json(out, mech, sweep, table, dynamics ? &*dynamics : nullptr);
  else if (args.format == "table")
    nbar::io::write_text_table(out, table);
  else
    nbar::io::write_csv(out, table);
  out.flush();

  for (const std::string& w : sweep.warnings) std::cerr << "warning: " << w << '\n';
  if (dynamics)
    for (const std::string& w : dynamics->warnings) std::cerr << "warning: " << w << '\n';
  return finish(args.model, sweep);
}

struct StressArgs {
  std::string model;
  std::optional<int> steps;
  int sections = 200;
  std::string format = "table";
  std::string output;
  std::string profile_body;
  std::optional<int> profile_step;
};

int run_stress(const StressArgs& args) {
  Loaded loaded;
  if (int code = load(args.model, loaded)) return code;
  const nbar::Mechanism& mech = *loaded.mechanism;
  const nbar::Model& m = mech.model();
  nbar::SweepOptions options;
  options.steps = args.steps;
  options.order = 2;
  nbar::SweepResult sweep;
  if (int code = sweep_model(args.model, mech, options, sweep)) return code;
  const nbar::InverseDynamics dynamics(mech);
  const nbar::LinkStress stress(dynamics, args.sections);
  bool any = false;
  for (std::size_t b = 0; b < m.bodies.size(); ++b) any = any || stress.analysed(static_cast<int>(b));
  if (!any) {
    std::cerr << "error: " << args.model << ": no link has a shape (`shape:` or `bar:` with a thickness), so "
              << "there is nothing to compute stresses in\n";
    return kInvalidModel;
  }

  Output output;
  if (!output.open(args.output)) return kBadUsage;
  std::ostream& out = output.stream();
  try {
    if (!args.profile_body.empty()) {
      const int body = m.find_body(args.profile_body);
      if (body < 0 || !stress.analysed(body)) {
        std::cerr << "error: --section-profile: '" << args.profile_body
                  << (body < 0 ? "' is not a body of the model\n" : "' has no shape to cut\n");
        return kBadUsage;
      }
      const int step = args.profile_step.value_or(0);
      if (step < 0 || step >= static_cast<int>(sweep.samples.size())) {
        std::cerr << "error: --step " << step << " is not a solved step (0 to " << sweep.samples.size() - 1 << ")\n";
        return kBadUsage;
      }
      const nbar::Sample& sample = sweep.samples[step];
      const auto profile = stress.profile(sample, dynamics.solve(sample), body);
      nbar::ResultTable t;
      t.columns = {"x", "area", "N", "V", "M", "sigma_right", "sigma_left", "tau", "von_mises"};
      const std::string len = m.units.length;
      t.units = {len, len + "^2", "N", "N", "N m", "MPa", "MPa", "MPa", "MPa"};
      const double unit = m.units.length_scale;
      for (const nbar::SectionStress& sec : profile)
        t.rows.push_back({sec.position / unit, sec.area / (unit * unit), sec.axial, sec.shear, sec.moment,
                          sec.sigma_low / 1e6, sec.sigma_high / 1e6, sec.tau_max / 1e6, sec.von_mises / 1e6});
      if (args.format == "json")
        nbar::io::write_json(out, mech, sweep, t);
      else if (args.format == "csv")
        nbar::io::write_csv(out, t);
      else
        nbar::io::write_text_table(out, t);
    } else {
      nbar::io::write_stress_report(out, args.format, mech, sweep, nbar::stress_peaks(dynamics, stress, sweep));
    }
  } catch (const std::domain_error& e) {
    std::cerr << "error: " << args.model << ": " << e.what() << '\n';
    return kInvalidModel;
  }
  out.flush();
  return finish(args.model, sweep);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"nbar: analysis of planar linkages (n-bar mechanisms)"};
  app.set_version_flag("--version", "nbar 0.1.0");
  app.require_subcommand(1);
  app.footer(
      "Exit codes: 0 success, 1 invalid model, 2 bad usage, 3 cannot assemble at the start,\n"
      "            4 sweep stopped early (the rows solved so far are written).\n"
      "Model files: see docs/model-format.md.");

  std::string check_model;
  CLI::App* check = app.add_subcommand("check", "Summarise a model: bodies, joints, degrees of freedom, redundant "
                                                "constraints, drivers, assembly at the start, Grashof class of "
                                                "every four-bar loop");
  check->add_option("MODEL", check_model, "model file (YAML or JSON)")->required();

  SolveArgs solve_args;
  CLI::App* solve = app.add_subcommand("solve", "Sweep the drivers and write positions, velocities, accelerations "
                                                "and higher derivatives of every point and body");
  solve->add_option("MODEL", solve_args.model, "model file (YAML or JSON)")->required();
  solve->add_option("--steps", solve_args.steps, "number of samples, ends included (overrides the model's sweep)")
      ->check(CLI::PositiveNumber);
  solve->add_option("--order", solve_args.order, "highest time derivative: 0 positions, 1 velocities, 2 "
                                                 "accelerations (default), 3 jerk, up to 5")
      ->check(CLI::Range(0, 5));
  solve->add_option("--format", solve_args.format, "csv (default), json, or table (aligned, for reading)")
      ->check(CLI::IsMember({"csv", "json", "table"}));
  solve->add_option("--columns", solve_args.columns,
                    "only these columns, comma-separated names or globs, e.g. 'crank,rocker.*,B.v*'")
      ->delimiter(',');
  solve->add_option("-o,--output", solve_args.output, "write to FILE instead of standard output");

  solve->add_flag("--dynamics", solve_args.dynamics,
                  "add inverse dynamics: the force at every joint, every driver's torque or force, energies "
                  "(N, N m, J whatever the length unit; order at least 2)");

  StressArgs stress_args;
  CLI::App* stress = app.add_subcommand("stress", "Stresses in every link that has a shape: the largest von Mises "
                                                  "stress over the sweep, where and when, and the safety factor");
  stress->add_option("MODEL", stress_args.model, "model file (YAML or JSON)")->required();
  stress->add_option("--steps", stress_args.steps, "number of samples, ends included (overrides the model's sweep)")
      ->check(CLI::PositiveNumber);
  stress->add_option("--sections", stress_args.sections, "cross-sections per link, at least (default 200)")
      ->check(CLI::Range(10, 100000));
  stress->add_option("--format", stress_args.format, "table (default), csv or json")
      ->check(CLI::IsMember({"table", "csv", "json"}));
  stress->add_option("-o,--output", stress_args.output, "write to FILE instead of standard output");
  CLI::Option* profile = stress->add_option("--section-profile", stress_args.profile_body,
                                            "instead, every section of BODY at one step: N, V, M, sigma, tau, von Mises");
  stress->add_option("--step", stress_args.profile_step, "the step for --section-profile (default 0)")->needs(profile);

  // Commands defined in their own files (commands.hpp).
  std::vector<std::pair<CLI::App*, std::function<int()>>> more;
  for (const auto& add : nbar::cli::more_commands()) more.push_back(add(app));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kOk : kBadUsage;
  }
  if (check->parsed()) return run_check(check_model);
  if (solve->parsed()) return run_solve(solve_args);
  if (stress->parsed()) return run_stress(stress_args);
  for (const auto& [command, run] : more) if (command->parsed()) return run();
  return kBadUsage;
}
