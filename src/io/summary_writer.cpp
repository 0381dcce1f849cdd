#include "nbar/io/summary_writer.hpp"

#include <fmt/format.h>

#include "nbar/kinematics/continuation.hpp"

namespace nbar::io {

namespace {

std::string join(const std::vector<std::string>& items, const std::string& separator = ", ") {
  std::string s;
  for (std::size_t i = 0; i < items.size(); ++i) s += (i ? separator : "") + items[i];
  return s;
}

std::string length_text(const Model& m, double si) {
  return fmt::format("{:.6g} {}", si / m.units.length_scale, m.units.length);
}

std::string plural(std::size_t n) { return n == 1 ? "" : "s"; }

void write_structure(std::ostream& out, const Model& m, const ModelSummary& s, const std::string& source) {
  out << "Model: " << (m.name.empty() ? std::string("(unnamed)") : m.name) << "  [" << source << "]\n";
  out << "Units: length " << m.units.length << ", angle " << m.units.angle << ", time s\n";
  out << fmt::format("Points: {} ({} fixed: {}; {} moving: {})\n", m.points.size(), s.ground_points.size(),
                     join(s.ground_points), s.moving_points.size(), join(s.moving_points));
  out << "Bodies: " << m.bodies.size() << '\n';
  for (const BodySummary& b : s.bodies) {
    const std::string extra =
        b.length ? "  length " + length_text(m, *b.length) + (b.length_given ? " (given)" : "") : std::string();
    out << fmt::format("  {:<12} [{}]{}\n", b.name, join(b.points), extra);
  }
  out << "Joints: " << s.joints.size() << '\n';
  for (const std::string& j : s.joints) out << "  " << j << '\n';
}

void write_mobility(std::ostream& out, const ModelSummary& s) {
  const MobilityReport& mob = s.mobility;
  out << fmt::format(
      "Degrees of freedom: {} (Gruebler-Kutzbach count {}; {} coordinates, {} constraint equations of rank {})\n",
      mob.dof, mob.grubler, mob.coordinates, mob.constraint_rows, mob.rank);
  if (mob.grubler != mob.dof)
    out << "  note: the count and the true mobility differ: the linkage has special geometry (redundant constraints)\n";
  if (s.redundant.empty()) {
    out << "Redundant constraints: none\n";
  } else {
    out << "Redundant constraints: " << s.redundant.size()
        << " (these depend on the others; the choice among a dependent set is arbitrary)\n";
    for (const std::string& label : s.redundant) out << "  " << label << '\n';
  }
  out << "Drivers: " << s.drivers.size() << '\n';
  for (const std::string& d : s.drivers) out << "  " << d << '\n';
}

void write_kinetics(std::ostream& out, const Model& m, const ModelSummary& s) {
  if (!s.has_mass_data && !s.has_loads) return;
  const double unit = m.units.length_scale;
  out << fmt::format("Mass properties (mass kg, centre of mass in {}, inertia about it kg m^2, plate area {}^2):\n",
                     m.units.length, m.units.length);
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    const BodySummary& b = s.bodies[i];
    const MassProperties& mp = b.mass;
    const std::string area =
        mp.from_shape || m.bodies[i].shape ? fmt::format("  area {:.6g}", mp.area / (unit * unit)) : "";
    if (mp.mass > 0.0)
      out << fmt::format("  {:<12} mass {:.6g}  cg ({:.6g}, {:.6g})  inertia {:.6g}{}  [{}]\n", b.name, mp.mass,
                         mp.cg.x() / unit, mp.cg.y() / unit, mp.inertia, area, b.mass_source);
    else  // no centre of mass to speak of
      out << fmt::format("  {:<12} mass 0{}  [{}]\n", b.name, area, b.mass_source);
  }
  out << fmt::format("Loads: gravity ({:.6g}, {:.6g}) m/s^2, {} point force{}, {} torque{}, {} spring{}\n",
                     m.gravity.x(), m.gravity.y(), m.point_loads.size(), plural(m.point_loads.size()),
                     m.torques.size(), plural(m.torques.size()), m.springs.size(), plural(m.springs.size()));
}

void write_start(std::ostream& out, const Model& m, const ModelSummary& s) {
  if (!s.assembly) {
    if (s.assembly_error && s.assembly_error->kind() == ErrorKind::CannotAssemble)
      out << "Assembly at the start: FAILED\n";
    return;
  }
  std::vector<std::string> at;
  for (std::size_t d = 0; d < s.assembly->driver_values.size(); ++d)
    at.push_back(m.drivers[d].name + " = " +
                 format_driver_value(m, static_cast<int>(d), s.assembly->driver_values[d]));
  out << fmt::format("Assembly at the start ({}): converged, residual {:.3g} {}\n", join(at),
                     s.assembly->residual / m.units.length_scale, m.units.length);
  if (s.assembly->passed_singularity)
    out << "  warning: reaching the start from the drawn pose passed a singular position\n";
  if (s.loops.empty()) {
    out << "Four-bar loops: none\n";
    return;
  }
  out << "Four-bar loops: " << s.loops.size() << '\n';
  for (const LoopSummary& l : s.loops) {
    out << "  " << l.loop.name << ": " << l.description << '\n';
    out << fmt::format("    at the start: {} branch, transmission angle {:.4g} {}\n", l.branch,
                       l.transmission_angle / m.units.angle_scale, m.units.angle);
  }
}

}  // namespace

void write_summary_text(std::ostream& out, const Mechanism& mechanism, const ModelSummary& summary,
                        const std::string& source) {
  const Model& m = mechanism.model();
  write_structure(out, m, summary, source);
  write_mobility(out, summary);
  write_kinetics(out, m, summary);
  write_start(out, m, summary);
  if (!summary.warnings.empty()) {
    out << "Warnings: " << summary.warnings.size() << '\n';
    for (const Warning& w : summary.warnings) out << "  warning: " << w.message << '\n';
  }
}

}  // namespace nbar::io
