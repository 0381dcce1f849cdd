// The explanation as a document: plain text, Markdown with LaTeX maths, or a LaTeX fragment.
// One walk through the sections; each format says how a heading, an equation, a vector, a
// matrix and a table look.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "explain_expr.hpp"
#include "nbar/analysis/explain.hpp"

namespace nbar {

namespace {

using explain_detail::clean;
using explain_detail::latex_name;
using explain_detail::latex_number;
using explain_detail::number;
using explain_detail::tex_escape;

constexpr int kWideMatrix = 8;  // columns beyond which Markdown and LaTeX list non-zeros instead

double max_abs_entry(const Eigen::MatrixXd& m) { return m.size() ? m.cwiseAbs().maxCoeff() : 0.0; }

// Rows of cells in aligned columns: the first left-aligned, the others right-aligned.
std::string aligned(const std::vector<std::vector<std::string>>& rows, const std::string& indent = "  ") {
  std::vector<std::size_t> width;
  for (const auto& r : rows)
    for (std::size_t c = 0; c < r.size(); ++c) {
      if (width.size() <= c) width.push_back(0);
      width[c] = std::max(width[c], r[c].size());
    }
  std::string out;
  for (const auto& r : rows) {
    std::string line = indent;
    for (std::size_t c = 0; c < r.size(); ++c) {
      const std::string pad(width[c] - r[c].size(), ' ');
      line += c == 0 ? r[c] + pad : "  " + pad + r[c];
    }
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out += line + "\n";
  }
  return out;
}

std::string md_table(const std::vector<std::string>& head, const std::vector<std::vector<std::string>>& rows) {
  std::string out = "|";
  for (const auto& h : head) out += " " + h + " |";
  out += "\n|";
  for (std::size_t c = 0; c < head.size(); ++c) out += c == 0 ? " --- |" : " ---: |";
  out += "\n";
  for (const auto& r : rows) {
    out += "|";
    for (const auto& cell : r) out += " " + cell + " |";
    out += "\n";
  }
  return out;
}

std::string tex_table(const std::vector<std::string>& head, const std::vector<std::vector<std::string>>& rows) {
  std::string out = "\\begin{tabular}{l" + std::string(head.size() - 1, 'r') + "}\n";
  for (std::size_t c = 0; c < head.size(); ++c) out += (c ? " & " : "") + head[c];
  out += " \\\\\n\\hline\n";
  for (const auto& r : rows) {
    for (std::size_t c = 0; c < r.size(); ++c) out += (c ? " & " : "") + r[c];
    out += " \\\\\n";
  }
  return out + "\\end{tabular}\n\n";
}

// Markdown would read q_k ... q_k as emphasis: escape _ and * outside $maths$.
std::string md_escape(const std::string& s) {
  std::string out;
  bool maths = false;
  for (char ch : s) {
    if (ch == '$') maths = !maths;
    if (!maths && (ch == '_' || ch == '*')) out += '\\';
    out += ch;
  }
  return out;
}

// A name or label as literal Markdown text: nothing in it starts emphasis, code, maths, a link, an
// HTML tag or a table cell (the characters CommonMark lets a backslash escape).
std::string md_literal(const std::string& s) {
  std::string out;
  for (char ch : s) {
    if (ch == '\\' || ch == '`' || ch == '*' || ch == '_' || ch == '|' || ch == '$' || ch == '<' || ch == '[' ||
        ch == ']')
      out += '\\';
    out += ch;
  }
  return out;
}

class Renderer {
 public:
  Renderer(const Explanation& ex, ExplainFormat f) : ex_(ex), f_(f), m_(ex.mechanism->model()) {
    const double lu = m_.units.length_scale;
    lc_ = ex.mechanism->characteristic_length() / lu;
    for (const Coordinate& c : ex.coordinates) {
      sym_.push_back(c.symbol);
      const std::string a = c.axis == 0 ? "x" : "y";
      tsym_.push_back(a + "_{" + latex_name(m_.points[c.point].name) + "}");
    }
  }

  std::string render() {
    title();
    count();
    coordinates();
    equations();
    symbolic_jacobian();
    newton();
    numeric_jacobian();
    motion(false);
    motion(true);
    centres();
    stresses();
    notes();
    return out_.str();
  }

 private:
  bool text() const { return f_ == ExplainFormat::Text; }
  bool md() const { return f_ == ExplainFormat::Markdown; }
  bool tex() const { return f_ == ExplainFormat::Latex; }

  // A number as the format writes it (LaTeX maths in Markdown and LaTeX tables).
  std::string n(double v) const { return text() ? number(v) : latex_number(v); }
  std::string cell(double v) const { return text() ? number(v) : "$" + latex_number(v) + "$"; }
  std::string cell3(double v) const { return text() ? number(v, 3) : "$" + latex_number(v, 3) + "$"; }
  std::string sym(std::size_t c) const { return text() ? sym_[c] : tsym_[c]; }
  // Words that hold the model's names (labels, its title) as literal text of the format.
  std::string words(const std::string& t) const { return text() ? t : tex() ? tex_escape(t) : md_literal(t); }

  // A heading; `words` and `maths` (LaTeX) replace the plain text's tail in Markdown and LaTeX.
  void heading(const std::string& t, const std::string& words = {}, const std::string& maths = {}) {
    if (text())
      out_ << "\n" << t << "\n" << std::string(t.size(), '-') << "\n";
    else if (md())
      out_ << "\n### " << (maths.empty() ? t : words + "$" + maths + "$") << "\n\n";
    else
      out_ << "\n\\subsection*{" << (maths.empty() ? tex_escape(t) : tex_escape(words) + "$" + maths + "$") << "}\n";
  }
  void para(const std::string& t) {
    if (text())
      out_ << wrap(t) << "\n";
    else
      out_ << (tex() ? tex_escape(t) : md_escape(t)) << "\n\n";
  }
  // Displayed maths: plain text form and LaTeX form.
  void display(const std::string& plain, const std::string& latex) {
    if (text())
      out_ << "  " << plain << "\n";
    else if (md())
      out_ << "$$" << latex << "$$\n\n";
    else
      out_ << "\\[ " << latex << " \\]\n";
  }
  // Words filled to `width` columns; continuation lines indented by `hang` spaces.
  static std::string wrap(const std::string& t, std::size_t hang = 0, std::size_t width = 92) {
    std::size_t lead = t.find_first_not_of(' ');
    if (lead == std::string::npos) lead = 0;
    std::istringstream words(t);
    std::string word, line = t.substr(0, lead), out;
    bool empty = true;
    while (words >> word) {
      if (!empty && line.size() + 1 + word.size() > width) {
        out += line + "\n";
        line = std::string(hang, ' ');
        empty = true;
      }
      line += (empty ? "" : " ") + word;
      empty = false;
    }
    return out + line;
  }

  std::string driver_symbol(int d, bool latex) const {
    const Driver& drv = m_.drivers[d];
    if (latex) return std::string(drv.is_angular() ? "\\theta_{" : "s_{") + latex_name(drv.name) + "}";
    return std::string(drv.is_angular() ? "th_" : "s_") + explain_detail::plain_name(drv.name);
  }
  std::string driver_value(int d, bool latex) const {
    const Driver& drv = m_.drivers[d];
    const double v = ex_.driver_values[d];
    const double si = v * (drv.is_angular() ? m_.units.angle_scale : m_.units.length_scale);
    const std::string num =
        latex ? latex_number(clean(v, 1e-12 * std::max(1.0, std::abs(v)))) : number(clean(v, 1e-12));
    if (drv.is_angular()) {
      if (m_.units.angle == "rad") return num + (latex ? "\\ \\mathrm{rad}" : " rad");
      return latex ? num + "^{\\circ} = " + latex_number(clean(si, 1e-15)) + "\\ \\mathrm{rad}"
                   : num + " " + m_.units.angle + " = " + number(clean(si, 1e-15)) + " rad";
    }
    return num + (latex ? "\\ \\mathrm{" + m_.units.length + "}" : " " + m_.units.length);
  }

  void title() {
    std::ostringstream t;
    t << "Step by step: " << (m_.name.empty() ? std::string("the model") : m_.name) << ", step " << ex_.step
      << " (t = " << number(clean(ex_.time, 1e-15)) << " s)";
    if (text())
      out_ << t.str() << "\n" << std::string(t.str().size(), '=') << "\n";
    else if (md())
      out_ << "## " << words(t.str()) << "\n";
    else
      out_ << "% Needs \\usepackage{amsmath}.\n\\section*{" << words(t.str()) << "}\n";
    std::string units = "Lengths in " + m_.units.length + ", angles in " + m_.units.angle +
                        ", time in s. Every equation below is a row the solver itself solves, written with the "
                        "model's names and numbers.";
    para(units);
    for (std::size_t d = 0; d < m_.drivers.size(); ++d)
      display("driver " + m_.drivers[d].name + ": " + driver_symbol(static_cast<int>(d), false) +
                  "(t) = " + driver_value(static_cast<int>(d), false),
              driver_symbol(static_cast<int>(d), true) + "(t) = " + driver_value(static_cast<int>(d), true));
  }

  void count() {
    const GrueblerCount& c = ex_.count;
    heading("1. Degrees of freedom (Gruebler-Kutzbach)");
    para(
        "n links (the ground included), PI one-freedom pairs (a revolute joint for each extra link meeting at a "
        "point, and each slider), PII two-freedom pairs (pins in slots):");
    std::ostringstream p, l;
    p << "n = " << c.links << ", PI = " << c.lower_pairs << ", PII = " << c.higher_pairs;
    l << "n = " << c.links << ",\\quad P_{I} = " << c.lower_pairs << ",\\quad P_{II} = " << c.higher_pairs;
    display(p.str(), l.str());
    std::ostringstream g, gl;
    g << "G = 3 (n - 1) - 2 PI - PII = 3 (" << c.links << " - 1) - 2*" << c.lower_pairs << " - " << c.higher_pairs
      << " = " << c.dof;
    gl << "G = 3(n-1) - 2P_{I} - P_{II} = 3(" << c.links << "-1) - 2\\cdot " << c.lower_pairs << " - " << c.higher_pairs
       << " = " << c.dof;
    display(g.str(), gl.str());
    std::ostringstream s;
    s << "The true mobility, the number of coordinates minus the rank of the constraint Jacobian, is " << c.mobility
      << (c.mobility == c.dof ? ", as counted." : ": the count differs because some constraints are redundant.");
    para(s.str());
  }

  void coordinates() {
    heading("2. The coordinates q", "2. The coordinates ", "\\mathbf{q}");
    para("nbar uses natural coordinates: q holds the x and y of every moving point (" +
         std::to_string(ex_.coordinates.size()) +
         " coordinates). There are no angle coordinates: each driver is a known function of time that enters "
         "through its own equation, a driver row of Phi.");
    std::string plain = "q = [", latex = "\\mathbf{q} = \\begin{bmatrix} ";
    for (std::size_t c = 0; c < sym_.size(); ++c) {
      plain += (c ? ", " : "") + sym_[c];
      latex += (c ? " & " : "") + tsym_[c];
    }
    display(plain + "]^T", latex + " \\end{bmatrix}^{T}");
    std::string fixed_plain, fixed_latex;
    for (std::size_t p = 0; p < m_.points.size(); ++p) {
      if (!m_.points[p].ground) continue;
      const Eigen::Vector2d r = m_.points[p].position / m_.units.length_scale;
      fixed_plain +=
          (fixed_plain.empty() ? "" : ", ") + m_.points[p].name + " = (" + number(r.x()) + ", " + number(r.y()) + ")";
      fixed_latex += (fixed_latex.empty() ? "" : ",\\quad ") + latex_name(m_.points[p].name) + " = (" +
                     latex_number(r.x()) + ", " + latex_number(r.y()) + ")";
    }
    if (!fixed_plain.empty()) {
      para("The fixed points are data, not unknowns; they appear in the equations as numbers:");
      display(fixed_plain, fixed_latex);
    }
  }

  void equations() {
    heading("3. Constraint equations Phi(q, t) = 0", "3. Constraint equations ", "\\Phi(\\mathbf{q}, t) = \\mathbf{0}");
    std::ostringstream s;
    s << ex_.equations.size() << " rows: the joints and the shapes of the links, then one row per driver. The solver "
      << "multiplies each row by a constant so that its residual is a length (shown as 'scale').";
    para(s.str());
    if (md()) out_ << "\n";
    for (std::size_t r = 0; r < ex_.equations.size(); ++r) {
      const EquationRow& e = ex_.equations[r];
      // The kind (point_on_line) is a word of nbar's, not a name: Markdown reads its _ as letters.
      const std::string kind = tex() ? tex_escape(e.kind) : e.kind;
      const std::string head =
          std::to_string(r + 1) + ". " + words(e.label) + " [" + kind + "], scale " + number(e.scale);
      if (text()) {
        out_ << "  " << head << "\n      " << e.text << "\n";
      } else if (md()) {
        out_ << "**" << head << "**\n$$" << e.latex << "$$\n\n";
      } else {
        out_ << "\\noindent " << head << "\n\\[ " << e.latex << " \\]\n";
      }
    }
  }

  void symbolic_jacobian() {
    heading("4. The Jacobian Phi_q, symbolically", "4. The Jacobian, symbolically: ", "\\Phi_{\\mathbf{q}}");
    para("The non-zero derivatives of each row (before the row's scale), one a line:");
    for (std::size_t r = 0; r < ex_.equations.size(); ++r) {
      const EquationRow& e = ex_.equations[r];
      std::string plain, latex;
      for (const auto& d : e.jacobian) {
        if (plain.empty()) {
          plain.append("  ").append(std::to_string(r + 1)).append(": ");
        } else {
          plain.append("\n").append(std::to_string(r + 1).size() + 4, ' ');
        }
        plain.append("d/d").append(sym_[d.column]).append(" = ").append(d.text);
        latex += (latex.empty() ? "" : " \\\\ ") + ("\\frac{\\partial\\Phi_{" + std::to_string(r + 1) +
                                                    "}}{\\partial " + tsym_[d.column] + "} &= " + d.latex);
      }
      if (text())
        out_ << plain << "\n";
      else if (md())  // one derivative a line: narrow enough for a phone
        out_ << "$$\\begin{aligned}" << latex << "\\end{aligned}$$\n\n";
      else
        out_ << "\\[ \\begin{aligned}" << latex << "\\end{aligned} \\]\n";
    }
  }

  void newton() {
    heading("5. Position: Newton-Raphson");
    std::ostringstream s;
    s << "Solve Phi_q(q_k) dq = -Phi(q_k), then q_(k+1) = q_k + dq, from " << ex_.start
      << " with the drivers at this step's values, until max |Phi| is below the solver's tolerance ("
      << number(ex_.mechanism->tolerance() / m_.units.length_scale, 3) << " " << m_.units.length
      << "). These are the iterations of the solver the sweep uses.";
    para(s.str());
    std::vector<std::vector<std::string>> rows;
    for (const NewtonIteration& it : ex_.newton) {
      const double step = it.dq.size() ? it.dq.cwiseAbs().maxCoeff() : 0.0;
      rows.push_back({std::to_string(it.iteration), cell3(it.residual), it.dq.size() ? cell3(step) : "-"});
    }
    const std::string unit = "(" + m_.units.length + ")";
    if (text()) {
      rows.insert(rows.begin(), {"k", "max|Phi| " + unit, "max|dq| " + unit});
      out_ << aligned(rows);
      // The iterates, one column each (the last few when there are many).
      const std::size_t first = ex_.newton.size() > 6 ? ex_.newton.size() - 6 : 0;
      std::vector<std::vector<std::string>> q(sym_.size() + 1);
      q[0].push_back("");
      for (std::size_t c = 0; c < sym_.size(); ++c) q[c + 1].push_back(sym_[c]);
      for (std::size_t k = first; k < ex_.newton.size(); ++k) {
        q[0].push_back("q_" + std::to_string(k));
        for (std::size_t c = 0; c < sym_.size(); ++c)
          q[c + 1].push_back(number(clean(ex_.newton[k].q[c], 1e-12 * lc_), 9));
      }
      out_ << "\n" << aligned(q);
    } else {
      const std::vector<std::string> head{"$k$", "$\\max\\lvert\\Phi\\rvert$ " + unit,
                                          "$\\max\\lvert\\Delta q\\rvert$ " + unit};
      out_ << (md() ? md_table(head, rows) + "\n" : tex_table(head, rows));
      // The last few iterates, narrow enough for a phone.
      const std::size_t first = ex_.newton.size() > 4 ? ex_.newton.size() - 4 : 0;
      std::string latex = "\\begin{array}{c|" + std::string(ex_.newton.size() - first, 'r') + "} & ";
      for (std::size_t k = first; k < ex_.newton.size(); ++k)
        latex += (k > first ? " & " : "") + ("q_{" + std::to_string(k) + "}");
      latex += " \\\\ \\hline ";
      for (std::size_t c = 0; c < sym_.size(); ++c) {
        latex += tsym_[c];
        for (std::size_t k = first; k < ex_.newton.size(); ++k)
          latex += " & " + latex_number(clean(ex_.newton[k].q[c], 1e-12 * lc_), 9);
        latex += " \\\\ ";
      }
      display("", latex + "\\end{array}");
    }
    std::ostringstream e;
    const std::size_t iterations = ex_.newton.empty() ? 0 : ex_.newton.size() - 1;
    e << (ex_.converged ? "Converged" : "Did not converge") << " after " << iterations
      << (iterations == 1 ? " iteration" : " iterations") << "; at the solution max |Phi| = " << number(ex_.residual, 3)
      << " " << m_.units.length << ".";
    if (ex_.converged && iterations == 0) {
      e << " There is nothing to iterate: " << ex_.start
        << " already meets every constraint to within the tolerance, so it is the solution.";
      if (ex_.step == 0) e << " A later step starts from the pose of the step before it and shows the iterations.";
    }
    if (ex_.converged && ex_.matches_sweep)
      e << " The solution is the sweep's sample " << ex_.step << " (they differ by " << number(ex_.sweep_difference, 3)
        << " " << m_.units.length << ").";
    para(e.str());
  }

  // A matrix: aligned in text; a bmatrix, or its non-zero entries when wide, in Markdown and LaTeX.
  void matrix(const Eigen::MatrixXd& a, const std::string& name_plain, const std::string& name_latex) {
    const double tol = 1e-12 * std::max(1.0, max_abs_entry(a));
    if (text()) {
      std::vector<std::vector<std::string>> rows(1, std::vector<std::string>{""});
      for (std::size_t c = 0; c < sym_.size(); ++c) rows[0].push_back(sym_[c]);
      for (Eigen::Index r = 0; r < a.rows(); ++r) {
        std::vector<std::string> row{std::to_string(r + 1)};
        for (Eigen::Index c = 0; c < a.cols(); ++c) row.push_back(a(r, c) == 0.0 ? "." : number(clean(a(r, c), tol)));
        rows.push_back(row);
      }
      out_ << "  " << name_plain << " (rows of Phi, columns of q; '.' is zero):\n" << aligned(rows);
      return;
    }
    if (a.cols() <= kWideMatrix) {
      std::string latex = name_latex + " = \\begin{bmatrix} ";
      for (Eigen::Index r = 0; r < a.rows(); ++r) {
        for (Eigen::Index c = 0; c < a.cols(); ++c) latex += (c ? " & " : "") + latex_number(clean(a(r, c), tol));
        latex += r + 1 < a.rows() ? " \\\\ " : " ";
      }
      display("", latex + "\\end{bmatrix}");
      return;
    }
    para("Its non-zero entries, row by row:");
    for (Eigen::Index r = 0; r < a.rows(); ++r) {
      std::string latex = "\\text{row } " + std::to_string(r + 1) + ":\\quad ";
      bool first = true;
      for (Eigen::Index c = 0; c < a.cols(); ++c) {
        if (a(r, c) == 0.0) continue;
        latex += (first ? "" : ",\\ ") + tsym_[c] + ": " + latex_number(clean(a(r, c), tol));
        first = false;
      }
      display("", latex);
    }
  }

  void numeric_jacobian() {
    heading("6. Phi_q at the solution", "6. At the solution: ", "\\Phi_{\\mathbf{q}}");
    para("Each row multiplied by its scale, as the solver factorises it (dimensionless).");
    matrix(ex_.jacobian, "Phi_q", "\\Phi_{\\mathbf{q}}");
  }

  void motion(bool acceleration) {
    const LinearSystem& s = acceleration ? ex_.acceleration : ex_.velocity;
    const std::string unit = m_.units.length + (acceleration ? "/s^2" : "/s");
    if (!acceleration) {
      heading("7. Velocity: Phi_q qdot = -Phi_t",
              "7. Velocity: ", "\\Phi_{\\mathbf{q}}\\dot{\\mathbf{q}} = -\\Phi_{t}");
      para(
          "Phi_t is the rate of change of Phi with the drivers moving and q held: it comes from the driver rows. "
          "The right-hand side and the solution are in " +
          unit + ".");
      display("Phi_q qdot = -Phi_t", "\\Phi_{\\mathbf{q}}\\,\\dot{\\mathbf{q}} = -\\Phi_{t}");
    } else {
      heading("8. Acceleration: Phi_q qddot = -(Phi_q qdot)_q qdot - 2 Phi_qt qdot - Phi_tt",
              "8. Acceleration: ", "\\Phi_{\\mathbf{q}}\\ddot{\\mathbf{q}} = \\dots");
      para("The right-hand side uses the velocities just found; Phi_q is the same matrix, factorised once. In " + unit +
           ".");
      display("Phi_q qddot = -(Phi_q qdot)_q qdot - 2 Phi_qt qdot - Phi_tt",
              "\\Phi_{\\mathbf{q}}\\,\\ddot{\\mathbf{q}} = -(\\Phi_{\\mathbf{q}}\\dot{\\mathbf{q}})_{\\mathbf{q}}\\,"
              "\\dot{\\mathbf{q}} - 2\\,\\Phi_{\\mathbf{q}t}\\,\\dot{\\mathbf{q}} - \\Phi_{tt}");
    }
    const double scale = std::max(max_abs_entry(s.solution), max_abs_entry(s.rhs));
    const double tol = 1e-10 * scale;
    const std::string rhs_name = acceleration ? "right-hand side" : "-Phi_t";
    std::vector<std::vector<std::string>> rhs_rows;
    for (Eigen::Index r = 0; r < s.rhs.size(); ++r)
      rhs_rows.push_back({std::to_string(r + 1) + " " + words(ex_.equations[r].label), cell(clean(s.rhs[r], tol))});
    std::vector<std::vector<std::string>> sol_rows;
    for (Eigen::Index c = 0; c < s.solution.size(); ++c)
      sol_rows.push_back({text() ? sym_[c] : "$" + tsym_[c] + "$", cell(clean(s.solution[c], tol))});
    const std::string dot = acceleration ? "qddot" : "qdot";
    const std::string ldot = acceleration ? "$\\ddot{q}$" : "$\\dot{q}$";
    if (text()) {
      rhs_rows.insert(rhs_rows.begin(), {"row", rhs_name});
      sol_rows.insert(sol_rows.begin(), {"q", dot});
      out_ << aligned(rhs_rows) << "\n" << aligned(sol_rows);
    } else {
      const std::string rhs_head = acceleration ? "right-hand side" : "$-\\Phi_t$";
      out_ << (md() ? md_table({"row", rhs_head}, rhs_rows) + "\n" : tex_table({"row", rhs_head}, rhs_rows));
      out_ << (md() ? md_table({"$q$", ldot}, sol_rows) + "\n" : tex_table({"$q$", ldot}, sol_rows));
    }
  }

  void centres() {
    heading("9. Instant centres");
    para(
        "For each pair of links (the ground included), the point where their velocities are equal, from each "
        "link's angular velocity and the velocity of one of its points. A primary centre is a revolute joint the "
        "two links share; links that translate relative to each other have their centre at infinity, in the "
        "direction given. By the Aronhold-Kennedy theorem, the three centres of any three links lie on one line.");
    std::vector<std::vector<std::string>> rows;
    for (const InstantCentre& c : ex_.centres) {
      std::string kind = c.at_joint        ? "primary (joint)"
                         : c.at_infinity   ? "at infinity"
                         : c.indeterminate ? "indeterminate"
                                           : "";
      if (c.at_infinity)
        rows.push_back({c.name, "-", "-",
                        kind + ", direction (" + number(clean(c.direction.x(), 1e-12)) + ", " +
                            number(clean(c.direction.y(), 1e-12)) + ")"});
      else if (c.indeterminate)
        rows.push_back({c.name, "-", "-", "no relative motion at this instant"});
      else
        rows.push_back(
            {c.name, cell(clean(c.position.x(), 1e-9 * lc_)), cell(clean(c.position.y(), 1e-9 * lc_)), kind});
    }
    const std::string x = "x (" + m_.units.length + ")", y = "y (" + m_.units.length + ")";
    if (text()) {
      rows.insert(rows.begin(), {"centre", x, y, ""});
      out_ << aligned(rows);
    } else {
      out_ << (md() ? md_table({"centre", x, y, "kind"}, rows) + "\n" : tex_table({"centre", x, y, "kind"}, rows));
    }
  }

  // Each shaped link's largest von Mises stress at this pose (Explanation::stresses), as `nbar
  // stress --section-profile LINK --step K` would find it among its sections.
  void stresses() {
    if (ex_.stresses.empty()) return;
    heading("10. Stresses at this pose");
    para(
        "For each link with a shape, the largest von Mises stress over its cross-sections under this pose's "
        "joint forces, driver efforts and inertia (the beam model of nbar stress), where along the link from its "
        "first point, and the safety factor when its material has a yield strength.");
    const double unit = m_.units.length_scale;
    const std::string x = "x (" + m_.units.length + ")";
    std::vector<std::vector<std::string>> rows;
    for (const StressPeak& p : ex_.stresses)
      rows.push_back({words(m_.bodies[p.body].name), cell(to_megapascal(p.at.von_mises)), cell(p.at.position / unit),
                      p.safety_factor ? cell3(*p.safety_factor) : "-"});
    const std::vector<std::string> head = {"link", "von Mises (MPa)", x, "safety factor"};
    if (text()) {
      rows.insert(rows.begin(), head);
      out_ << aligned(rows);
    } else {
      out_ << (md() ? md_table(head, rows) + "\n" : tex_table(head, rows));
    }
  }

  void notes() {
    if (ex_.notes.empty()) return;
    heading("Notes");
    for (const std::string& n : ex_.notes) {
      if (text())
        out_ << wrap("- " + n, 2) << "\n";
      else if (md())
        out_ << "- " << n << "\n";
      else
        out_ << "\\noindent " << tex_escape(n) << "\n\n";
    }
  }

  const Explanation& ex_;
  ExplainFormat f_;
  const Model& m_;
  double lc_ = 1.0;
  std::vector<std::string> sym_, tsym_;
  std::ostringstream out_;
};

}  // namespace

std::string render_explanation(const Explanation& explanation, ExplainFormat format) {
  if (!explanation.mechanism) throw Error(ErrorKind::BadInput, "an empty explanation");
  return Renderer(explanation, format).render();
}

}  // namespace nbar
