// The equations of motion at one time of a simulation as text (`nbar explain --simulate`): the
// system, its blocks with the names of q and of Phi's rows, Q by origin, gamma and the solution.
#include <algorithm>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "nbar/dynamics/equations_of_motion.hpp"

namespace nbar {

namespace {

using Table = std::vector<std::vector<std::string>>;

// printf's %g with `digits` significant digits (the core does not link fmt).
std::string number(double v, int digits = 6) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*g", digits, v + 0.0);
  return text;
}
// Rounding left by a solve (below 1e-12 of the largest entry of its vector or matrix) shown as 0.
std::string cleaned(double v, double largest) { return number(std::abs(v) < 1e-12 * largest ? 0.0 : v); }
double largest(const Eigen::MatrixXd& a) { return a.size() ? a.lpNorm<Eigen::Infinity>() : 0.0; }

// Columns right-aligned but the first (and the last, a row's label, when `label_last`), two
// spaces apart, indented by two.
std::string aligned(const Table& rows, bool label_last = false) {
  std::vector<std::size_t> width;
  for (const auto& row : rows) {
    width.resize(std::max(width.size(), row.size()), 0);
    for (std::size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], row[c].size());
  }
  std::string out;
  for (const auto& row : rows) {
    std::string line = " ";
    for (std::size_t c = 0; c < row.size(); ++c) {
      const std::string padding(width[c] - row[c].size(), ' ');
      const bool left = c == 0 || (label_last && c + 1 == row.size());
      line += (c ? "  " : " ") + (left ? row[c] + padding : padding + row[c]);
    }
    line.erase(line.find_last_not_of(' ') + 1);
    out += line + '\n';
  }
  return out;
}

void heading(std::ostringstream& out, const std::string& title) {
  out << '\n' << title << '\n' << std::string(title.size(), '-') << '\n';
}

// A matrix with its rows and columns named; '.' where an entry is exactly zero.
std::string matrix(const Eigen::MatrixXd& a, const std::vector<std::string>& rows,
                   const std::vector<std::string>& columns) {
  Table table(1, std::vector<std::string>{""});
  for (const std::string& c : columns) table[0].push_back(c);
  for (Eigen::Index r = 0; r < a.rows(); ++r) {
    table.push_back({rows[r]});
    for (Eigen::Index c = 0; c < a.cols(); ++c)
      table.back().push_back(a(r, c) == 0.0 ? "." : cleaned(a(r, c), largest(a)));
  }
  return aligned(table);
}

std::vector<std::string> row_numbers(std::size_t count) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < count; ++i) out.push_back(std::to_string(i + 1));
  return out;
}

void state_section(std::ostringstream& out, const EquationsOfMotionAt& e) {
  heading(out, "1. The state at t = " + number(e.time) + " s");
  Table t{{"", "q (m)", "q' (m/s)"}};
  for (Eigen::Index i = 0; i < e.q.size(); ++i) t.push_back({e.coordinates[i], number(e.q(i)), number(e.velocity(i))});
  out << aligned(t);
}

void forces_section(std::ostringstream& out, const EquationsOfMotionAt& e) {
  heading(out, "4. The generalised forces Q (N), by origin");
  out << "Each load's virtual work on q: gravity (sum of m C^T g), the given forces and torques (a torque\n"
         "T on a body enters at its two frame points as T (u x du)/|u|^2), the springs and dampers\n"
         "between their points, and joint friction (f grad s).\n";
  Table t{{"", "gravity", "given", "springs", "friction", "Q"}};
  for (Eigen::Index i = 0; i < e.q.size(); ++i)
    t.push_back({e.coordinates[i], cleaned(e.gravity(i), largest(e.gravity)), cleaned(e.applied(i), largest(e.applied)),
                 cleaned(e.springs(i), largest(e.springs)), cleaned(e.friction(i), largest(e.friction)),
                 cleaned(e.forces(i), largest(e.forces))});
  out << aligned(t);
}

void solution_section(std::ostringstream& out, const EquationsOfMotionAt& e) {
  heading(out, "6. The solution: accelerations and multipliers");
  Table t{{"", "q'' (m/s^2)"}};
  for (Eigen::Index i = 0; i < e.q.size(); ++i)
    t.push_back({e.coordinates[i], cleaned(e.acceleration(i), largest(e.acceleration))});
  out << aligned(t);
  Table l{{"", "lambda (N)", ""}};
  for (Eigen::Index r = 0; r < e.multipliers.size(); ++r)
    l.push_back({std::to_string(r + 1), cleaned(e.multipliers(r), largest(e.multipliers)), e.row_labels[r]});
  out << '\n' << aligned(l, true);
  const double difference = (e.acceleration - e.simulated_acceleration).lpNorm<Eigen::Infinity>();
  out << "\nSolved densely, with a relative residual of " << number(e.residual, 2)
      << "; the simulation's own row at this\ntime (its sparse augmented solve) has the same q'' to "
      << number(difference, 2) << " m/s^2.\n";
  out << "-Phi_q^T lambda is the force the joints and the kinematic drivers put on q.\n";
}

}  // namespace

std::string render_equations_of_motion(const Mechanism& mechanism, const EquationsOfMotionAt& e) {
  std::ostringstream out;
  const std::string title = "Equations of motion: " + mechanism.model().name + ", at t = " + number(e.time) + " s";
  out << title << '\n' << std::string(title.size(), '=') << '\n';
  if (e.time > 0.0)
    out << "The state is the one `nbar simulate --to " << number(e.time) << "` reaches (" << e.accepted_steps
        << " integration steps from the start).\n";
  else
    out << "The state is the start: the model's initial positions and speeds.\n";
  out << "At every evaluation the forward dynamics solves\n\n"
      << "  [ M      Phi_q^T ] [ q''    ]   [ Q     ]\n"
      << "  [ Phi_q  0       ] [ lambda ] = [ gamma ]\n\n"
      << "in the natural coordinates q (the x and y of every moving point). SI units: q in m, M in kg,\n"
      << "Q in N, gamma in m/s^2, lambda in N; each row of Phi is scaled as the solver scales it (its\n"
      << "residual a length), so Phi_q is dimensionless.\n";
  std::string free;
  for (const std::string& name : e.free_drivers) free += (free.empty() ? "" : ", ") + name;
  out << "Free drivers (their rows left out of Phi): " << free << ".\n";
  state_section(out, e);
  heading(out, "2. The mass matrix M (kg), constant");
  out << "Each body's mass on its frame points, sum of m C^T C + (I/|u|^2) D^T D (v_G = C q', u' = D q').\n";
  out << matrix(e.mass, e.coordinates, e.coordinates);
  heading(out, "3. The constraint Jacobian Phi_q (" + std::to_string(e.rows.size()) + " rows)");
  out << "The rows kept: the joints, the shapes of the links and the kinematic drivers.\n";
  for (std::size_t r = 0; r < e.row_labels.size(); ++r) out << "  " << r + 1 << ". " << e.row_labels[r] << '\n';
  out << '\n' << matrix(e.jacobian, row_numbers(e.rows.size()), e.coordinates);
  forces_section(out, e);
  heading(out, "5. gamma (m/s^2): Phi_q q'' = gamma");
  out << "gamma = -(Phi_q q')_q q' - 2 Phi_qt q' - Phi_tt, from the constraints' Taylor recursion.\n";
  Table g;
  for (Eigen::Index r = 0; r < e.gamma.size(); ++r)
    g.push_back({std::to_string(r + 1), cleaned(e.gamma(r), largest(e.gamma)), e.row_labels[r]});
  out << aligned(g, true);
  solution_section(out, e);
  return out.str();
}

}  // namespace nbar
