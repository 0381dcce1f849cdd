// The step-by-step explanation says what the solver does: its printed equations, evaluated by
// an expression evaluator of this test's own, give the solver's residuals and Jacobian; its
// Newton iterations end on the sweep's sample; its velocities and accelerations are the
// sweep's; its instant centres match the four-bar's closed form and Kennedy's theorem.
#include "example_models.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>

#include "io/explain_writer.hpp"
#include "kinematics/constraints.hpp"
#include "nbar/analysis/explain.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/kinematics/position.hpp"
#include "nbar/kinematics/sweep.hpp"

namespace nbar {
namespace {

using test_support::example_mechanism;

std::vector<std::string> all_examples() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(NBAR_EXAMPLES_DIR))
    if (entry.path().extension() == ".yaml") names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// An evaluator of the plain-text formulas: numbers (with exponents), symbols, + - * / ^,
// parentheses, unary minus, sin and cos. Written here, independently of the code that prints.
class Evaluator {
 public:
  explicit Evaluator(const std::map<std::string, double>& symbols) : symbols_(symbols) {}
  double operator()(const std::string& text) {
    s_ = text;
    i_ = 0;
    const double v = expression();
    skip();
    if (i_ != s_.size()) throw std::runtime_error("unparsed tail in '" + s_ + "' at " + std::to_string(i_));
    return v;
  }

 private:
  void skip() {
    while (i_ < s_.size() && s_[i_] == ' ') ++i_;
  }
  bool eat(char c) {
    skip();
    if (i_ < s_.size() && s_[i_] == c) {
      ++i_;
      return true;
    }
    return false;
  }
  double expression() {
    double v = term();
    for (;;) {
      if (eat('+'))
        v += term();
      else if (eat('-'))
        v -= term();
      else
        return v;
    }
  }
  double term() {
    double v = unary();
    for (;;) {
      if (eat('*'))
        v *= unary();
      else if (eat('/'))
        v /= unary();
      else
        return v;
    }
  }
  double unary() {
    if (eat('-')) return -unary();
    if (eat('+')) return unary();
    return power();
  }
  double power() {
    const double base = primary();
    if (eat('^')) return std::pow(base, unary());
    return base;
  }
  double primary() {
    skip();
    if (eat('(')) {
      const double v = expression();
      if (!eat(')')) throw std::runtime_error("missing ) in '" + s_ + "'");
      return v;
    }
    if (i_ < s_.size() && (std::isdigit(static_cast<unsigned char>(s_[i_])) || s_[i_] == '.')) {
      std::size_t used = 0;
      const double v = std::stod(s_.substr(i_), &used);
      i_ += used;
      return v;
    }
    std::string name;
    while (i_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[i_])) || s_[i_] == '_')) name += s_[i_++];
    if (name.empty()) throw std::runtime_error("unexpected character in '" + s_ + "' at " + std::to_string(i_));
    if (name == "sin" || name == "cos") {
      if (!eat('(')) throw std::runtime_error("sin/cos without (");
      const double a = expression();
      if (!eat(')')) throw std::runtime_error("missing ) after sin/cos argument");
      return name == "sin" ? std::sin(a) : std::cos(a);
    }
    const auto it = symbols_.find(name);
    if (it == symbols_.end()) throw std::runtime_error("unknown symbol '" + name + "'");
    return it->second;
  }

  const std::map<std::string, double>& symbols_;
  std::string s_;
  std::size_t i_ = 0;
};

std::string left_side(const std::string& equation) {
  const auto at = equation.rfind(" = 0");
  EXPECT_NE(at, std::string::npos) << equation;
  EXPECT_EQ(at + 4, equation.size()) << equation;
  return equation.substr(0, at);
}

// The symbols at q (model units): every coordinate, and the drivers (angles in radians, as sin
// and cos take them; lengths in model units).
std::map<std::string, double> symbols_at(const Explanation& ex, const Eigen::VectorXd& q) {
  const Model& m = ex.mechanism->model();
  std::map<std::string, double> s;
  for (std::size_t c = 0; c < ex.coordinates.size(); ++c) s[ex.coordinates[c].symbol] = q[static_cast<Eigen::Index>(c)];
  for (std::size_t d = 0; d < m.drivers.size(); ++d) {
    const bool angle = m.drivers[d].is_angular();
    s[(angle ? "th_" : "s_") + m.drivers[d].name] = ex.driver_values[d] * (angle ? m.units.angle_scale : 1.0);
  }
  return s;
}

std::vector<DriverState> drivers_at(const Explanation& ex) {
  const Model& m = ex.mechanism->model();
  std::vector<DriverState> out;
  for (std::size_t d = 0; d < m.drivers.size(); ++d) {
    const bool angle = m.drivers[d].is_angular();
    const double si = ex.driver_values[d] * (angle ? m.units.angle_scale : m.units.length_scale);
    out.push_back(make_driver_state(Series(1, si), angle));
  }
  return out;
}

Eigen::MatrixXd dense_jacobian(const Mechanism& mech, const Eigen::VectorXd& q_si, const std::vector<DriverState>& d) {
  std::vector<double> values;
  evaluate_jacobian(mech, q_si, d, values);
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(mech.row_count(), mech.coordinate_count());
  const auto& pattern = mech.equations().pattern;
  for (std::size_t e = 0; e < pattern.size(); ++e) j(pattern[e].row, pattern[e].col) += values[e];
  return j;
}

// Away from the solution, so that every row has a residual worth comparing.
Eigen::VectorXd perturbed(const Eigen::VectorXd& q, double size) {
  Eigen::VectorXd p = q;
  for (Eigen::Index i = 0; i < p.size(); ++i) p[i] += size * std::sin(1.3 + 2.1 * static_cast<double>(i));
  return p;
}

TEST(Explain, PrintedEquationsGiveTheSolversResidualsAndJacobianOnEveryExample) {
  int rows_checked = 0, entries_checked = 0;
  std::map<std::string, int> kinds;
  for (const std::string& name : all_examples()) {
    SCOPED_TRACE(name);
    const auto mech = example_mechanism(name);
    ExplainOptions options;
    options.steps = 13;
    options.step = 3;
    const Explanation ex = explain(mech, options);
    const double ls = mech->model().units.length_scale;
    const double lc = mech->characteristic_length() / ls;  // model units
    const Eigen::VectorXd q = perturbed(ex.q, 0.02 * lc);
    const auto drivers = drivers_at(ex);
    Eigen::VectorXd phi;
    evaluate_residuals(*mech, q * ls, drivers, phi);
    const Eigen::MatrixXd jac = dense_jacobian(*mech, q * ls, drivers);
    ASSERT_EQ(static_cast<int>(ex.equations.size()), mech->row_count());
    auto symbols = symbols_at(ex, q);
    Evaluator eval(symbols);
    for (std::size_t r = 0; r < ex.equations.size(); ++r) {
      const EquationRow& e = ex.equations[r];
      SCOPED_TRACE(e.label + ": " + e.text);
      ++kinds[e.kind];
      const std::string lhs = left_side(e.text);
      // The printed numbers have six significant digits: agreement to 1e-5 of the model's size.
      const double residual = phi[static_cast<Eigen::Index>(r)] / ls;
      ASSERT_GT(std::abs(residual) + std::abs(e.scale * eval(lhs)), 0.0);
      EXPECT_NEAR(e.scale * eval(lhs), residual, 1e-5 * lc);
      ++rows_checked;
      // Each printed derivative is the solver's Jacobian entry; every other entry is zero.
      std::vector<bool> listed(ex.coordinates.size(), false);
      for (const auto& d : e.jacobian) {
        listed[d.column] = true;
        EXPECT_NEAR(e.scale * eval(d.text), jac(static_cast<Eigen::Index>(r), d.column),
                    1e-5 * std::max(1.0, std::abs(jac(static_cast<Eigen::Index>(r), d.column))))
            << "d/d" << ex.coordinates[d.column].symbol << " = " << d.text;
        // And the derivative of the printed equation itself, by central differences.
        const std::string& s = ex.coordinates[d.column].symbol;
        const double h = 1e-4 * lc, keep = symbols[s];
        symbols[s] = keep + h;
        const double up = eval(lhs);
        symbols[s] = keep - h;
        const double down = eval(lhs);
        symbols[s] = keep;
        EXPECT_NEAR(e.scale * (up - down) / (2 * h), jac(static_cast<Eigen::Index>(r), d.column),
                    1e-5 * std::max(1.0, std::abs(jac(static_cast<Eigen::Index>(r), d.column))));
        ++entries_checked;
      }
      for (std::size_t c = 0; c < listed.size(); ++c)
        if (!listed[c]) {
          EXPECT_EQ(jac(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)), 0.0);
        }
    }
    // The numeric Phi_q at the solution is the solver's there.
    const Eigen::MatrixXd at_solution = dense_jacobian(*mech, ex.q * ls, drivers);
    EXPECT_LE((ex.jacobian - at_solution).cwiseAbs().maxCoeff(),
              1e-12 * std::max(1.0, at_solution.cwiseAbs().maxCoeff()));
  }
  // Every kind of row was written and checked somewhere.
  for (const char* kind : {"distance", "rigid_x", "rigid_y", "point_on_line", "orientation", "driver"})
    EXPECT_GT(kinds[kind], 0) << kind;
  EXPECT_GT(rows_checked, 150);
  EXPECT_GT(entries_checked, 500);
}

TEST(Explain, DriverRowsOfEveryKindAreWritten) {
  // Angle, relative angle, distance and slide drivers all appear among the examples.
  std::map<ConstraintType, int> seen;
  for (const std::string& name : all_examples()) {
    const auto mech = example_mechanism(name);
    for (const Constraint& c : mech->equations().rows)
      if (c.is_driver()) ++seen[c.type];
  }
  EXPECT_GT(seen[ConstraintType::DriveAngle], 0);
  EXPECT_GT(seen[ConstraintType::DriveSlide], 0);
  EXPECT_GT(seen[ConstraintType::DriveDistance] + seen[ConstraintType::DriveRelativeAngle], 0);
}

TEST(Explain, NewtonEndsOnTheSweepsSampleAndConvergesQuadratically) {
  const auto mech = example_mechanism("fourbar-crank-rocker.yaml");
  const double ls = mech->model().units.length_scale;
  const double lc = mech->characteristic_length() / ls;
  SweepOptions sweep_options;
  const SweepResult sweep = run_sweep(*mech, sweep_options);
  for (int step : {0, 1, 30, 200, 360}) {
    SCOPED_TRACE(step);
    ExplainOptions options;
    options.step = step;
    const Explanation ex = explain(mech, options);
    ASSERT_TRUE(ex.converged);
    EXPECT_TRUE(ex.matches_sweep);
    EXPECT_TRUE(ex.notes.empty());
    ASSERT_GE(ex.newton.size(), 2u);
    // It starts where it says.
    const Eigen::VectorXd start = step == 0 ? mech->drawn_coordinates() : sweep.samples[step - 1].positions();
    EXPECT_LE((ex.newton.front().q - start / ls).cwiseAbs().maxCoeff(), 1e-12 * lc);
    // Each step leads to the next iterate; the residual falls every time.
    for (std::size_t k = 0; k + 1 < ex.newton.size(); ++k) {
      ASSERT_EQ(ex.newton[k].dq.size(), ex.newton[k].q.size());
      EXPECT_LE((ex.newton[k].q + ex.newton[k].dq - ex.newton[k + 1].q).cwiseAbs().maxCoeff(), 1e-12 * lc);
      EXPECT_LT(ex.newton[k + 1].residual, ex.newton[k].residual);
    }
    EXPECT_EQ(ex.newton.back().dq.size(), 0);
    // The last iterate is the solution and the sweep's sample.
    EXPECT_LE(ex.newton.back().residual, mech->tolerance() / ls);
    EXPECT_LE((ex.newton.back().q - ex.q).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_LE((ex.q - sweep.samples[step].positions() / ls).cwiseAbs().maxCoeff(), 1e-9 * lc);
    EXPECT_DOUBLE_EQ(ex.residual, ex.newton.back().residual);
    // Quadratic convergence: from a step away (steps > 0), the relative residual's exponent
    // about doubles once it is small, until rounding.
    if (step > 0) {
      ASSERT_GE(ex.newton.size(), 4u);
      int quadratic = 0;
      for (std::size_t k = 1; k + 1 < ex.newton.size(); ++k) {
        const double e0 = ex.newton[k].residual / lc, e1 = ex.newton[k + 1].residual / lc;
        if (e1 < 1e-14 || e0 > 1e-2) continue;  // at rounding, or still far
        EXPECT_GT(std::log(e1) / std::log(e0), 1.6) << "k " << k << ": " << e0 << " -> " << e1;
        ++quadratic;
      }
      EXPECT_GE(quadratic, 1);
    }
  }
}

TEST(Explain, AFarStartOnAnotherBranchIsSaidNotHidden) {
  // Three samples: Newton from step 0's pose jumps half a turn and lands on the crossed branch.
  const auto mech = example_mechanism("fourbar-crank-rocker.yaml");
  ExplainOptions options;
  options.steps = 3;
  options.step = 1;
  const Explanation ex = explain(mech, options);
  EXPECT_TRUE(ex.converged);
  EXPECT_FALSE(ex.matches_sweep);
  EXPECT_GT(ex.sweep_difference, 1.0);
  ASSERT_FALSE(ex.notes.empty());
  EXPECT_NE(ex.notes.front().find("another solution than the sweep's"), std::string::npos);
  // What follows is the sweep's sample.
  const SweepResult sweep = run_sweep(*mech, SweepOptions{3, 2});
  EXPECT_LE((ex.q - sweep.samples[1].positions() / mech->model().units.length_scale).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_NE(render_explanation(ex, ExplainFormat::Text).find("another solution than the sweep's"), std::string::npos);
}

TEST(Explain, VelocitiesAndAccelerationsAreTheSweepsAndTheSystemsAreConsistent) {
  for (const std::string& name : all_examples()) {
    SCOPED_TRACE(name);
    const auto mech = example_mechanism(name);
    const double ls = mech->model().units.length_scale;
    const SweepResult sweep = run_sweep(*mech, SweepOptions{13, 2});
    for (int step : {0, 5}) {
      if (step >= static_cast<int>(sweep.samples.size())) continue;
      ExplainOptions options;
      options.steps = 13;
      options.step = step;
      const Explanation ex = explain(mech, options);
      const Sample& s = sweep.samples[step];
      const Eigen::VectorXd v = s.derivative(1) / ls, a = s.derivative(2) / ls;
      const double vs = std::max(1e-9, v.cwiseAbs().maxCoeff()), as = std::max(1e-9, a.cwiseAbs().maxCoeff());
      EXPECT_LE((ex.velocity.solution - v).cwiseAbs().maxCoeff(), 1e-9 * vs);
      EXPECT_LE((ex.acceleration.solution - a).cwiseAbs().maxCoeff(), 1e-9 * as);
      EXPECT_NEAR(ex.time, s.time, 1e-12);
      // matrix * solution == rhs, in the units printed.
      for (const LinearSystem* sys : {&ex.velocity, &ex.acceleration}) {
        const double size = std::max(sys->rhs.cwiseAbs().maxCoeff(),
                                     sys->matrix.cwiseAbs().maxCoeff() * sys->solution.cwiseAbs().maxCoeff());
        EXPECT_LE((sys->matrix * sys->solution - sys->rhs).cwiseAbs().maxCoeff(), 1e-10 * std::max(size, 1e-9));
        EXPECT_EQ(sys->matrix.rows(), mech->row_count());
      }
      // Phi_t comes from the driver rows alone: the others do not depend on time.
      for (int r = 0; r < mech->constraint_row_count(); ++r) EXPECT_EQ(ex.velocity.rhs[r], 0.0);
    }
  }
}

TEST(Explain, RedundantSystemsAreSolvedByLeastSquaresAndSaySo) {
  const auto mech = example_mechanism("parallelogram-redundant.yaml");
  const Explanation ex = explain(mech);
  EXPECT_GT(ex.jacobian.rows(), ex.jacobian.cols());
  bool said = false;
  for (const auto& n : ex.notes) said = said || n.find("least squares") != std::string::npos;
  EXPECT_TRUE(said);
  EXPECT_EQ(ex.count.dof, 0);
  EXPECT_EQ(ex.count.mobility, 1);
}

TEST(Explain, GrueblerCountsOfTheExamples) {
  struct Case {
    const char* file;
    int n, p1, p2, g;
  };
  for (const Case& c : {Case{"fourbar-crank-rocker.yaml", 4, 4, 0, 1}, Case{"slider-crank-offset.yaml", 4, 4, 0, 1},
                        Case{"inverted-slider-crank-shaper.yaml", 6, 7, 0, 1}, Case{"scissor-lift.yaml", 7, 8, 1, 1},
                        Case{"watt-sixbar.yaml", 6, 7, 0, 1}, Case{"five-bar.yaml", 5, 5, 0, 2}}) {
    SCOPED_TRACE(c.file);
    const Explanation ex = explain(example_mechanism(c.file));
    EXPECT_EQ(ex.count.links, c.n);
    EXPECT_EQ(ex.count.lower_pairs, c.p1);
    EXPECT_EQ(ex.count.higher_pairs, c.p2);
    EXPECT_EQ(ex.count.dof, c.g);
    EXPECT_EQ(ex.count.dof, 3 * (c.n - 1) - 2 * c.p1 - c.p2);
    EXPECT_EQ(ex.count.mobility, c.g);
    EXPECT_EQ(ex.count.dof, example_mechanism(c.file)->mobility().grubler);
  }
}

Eigen::Vector2d intersect(const Eigen::Vector2d& p1, const Eigen::Vector2d& p2, const Eigen::Vector2d& p3,
                          const Eigen::Vector2d& p4) {
  // p1 + s (p2 - p1) = p3 + t (p4 - p3)
  Eigen::Matrix2d a;
  a.col(0) = p2 - p1;
  a.col(1) = p3 - p4;
  const Eigen::Vector2d st = a.colPivHouseholderQr().solve(p3 - p1);
  return p1 + st[0] * (p2 - p1);
}

const InstantCentre& centre(const Explanation& ex, int a, int b) {
  for (const InstantCentre& c : ex.centres)
    if (c.body_a == a && c.body_b == b) return c;
  throw std::runtime_error("no centre");
}

TEST(Explain, InstantCentresOfTheCrankRockerMatchTheClosedForm) {
  const auto mech = example_mechanism("fourbar-crank-rocker.yaml");
  const Model& m = mech->model();
  const int crank = m.find_body("crank"), coupler = m.find_body("coupler"), rocker = m.find_body("rocker");
  for (int step : {10, 30, 100, 250}) {
    SCOPED_TRACE(step);
    ExplainOptions options;
    options.step = step;
    const Explanation ex = explain(mech, options);
    ASSERT_EQ(ex.centres.size(), 6u);  // 4 links: 4 * 3 / 2
    auto at = [&](const char* point) {
      const int p = m.find_point(point);
      const int col = mech->column_of(p);
      return col < 0 ? Eigen::Vector2d(m.points[p].position / m.units.length_scale)
                     : Eigen::Vector2d(ex.q.segment<2>(col));
    };
    const Eigen::Vector2d O2 = at("O2"), O4 = at("O4"), A = at("A"), B = at("B");
    const double tol = 1e-7 * mech->characteristic_length() / m.units.length_scale;
    // Primary centres at the pins.
    EXPECT_TRUE(centre(ex, -1, crank).at_joint);
    EXPECT_LE((centre(ex, -1, crank).position - O2).norm(), tol);
    EXPECT_LE((centre(ex, crank, coupler).position - A).norm(), tol);
    EXPECT_LE((centre(ex, coupler, rocker).position - B).norm(), tol);
    EXPECT_LE((centre(ex, -1, rocker).position - O4).norm(), tol);
    // I13 (ground, coupler) where O2A meets O4B; I24 (crank, rocker) where AB meets O2O4.
    const InstantCentre& i13 = centre(ex, -1, coupler);
    const InstantCentre& i24 = centre(ex, crank, rocker);
    EXPECT_FALSE(i13.at_joint || i13.at_infinity || i24.at_joint || i24.at_infinity);
    EXPECT_LE((i13.position - intersect(O2, A, O4, B)).norm(), tol) << i13.position.transpose();
    EXPECT_LE((i24.position - intersect(A, B, O2, O4)).norm(), tol) << i24.position.transpose();
  }
}

// Aronhold-Kennedy: the three centres of any three links lie on one line (a centre at infinity
// is a direction the line through the other two follows).
void expect_kennedy(const Explanation& ex, int& triples) {
  std::map<std::pair<int, int>, const InstantCentre*> by;
  std::vector<int> links{-1};
  for (const InstantCentre& c : ex.centres) {
    by[{c.body_a, c.body_b}] = &c;
    if (c.body_a == -1) links.push_back(c.body_b);
  }
  const double lc = ex.mechanism->characteristic_length() / ex.mechanism->model().units.length_scale;
  auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); };
  for (std::size_t i = 0; i < links.size(); ++i)
    for (std::size_t j = i + 1; j < links.size(); ++j)
      for (std::size_t k = j + 1; k < links.size(); ++k) {
        std::vector<const InstantCentre*> three{by.at({links[i], links[j]}), by.at({links[j], links[k]}),
                                                by.at({links[i], links[k]})};
        std::vector<Eigen::Vector2d> points, directions;
        bool indeterminate = false;
        for (const auto* c : three) {
          indeterminate = indeterminate || c->indeterminate;
          (c->at_infinity ? directions : points).push_back(c->at_infinity ? c->direction : c->position);
        }
        if (indeterminate) continue;
        SCOPED_TRACE(three[0]->name + " " + three[1]->name + " " + three[2]->name);
        if (points.size() == 3) {
          const Eigen::Vector2d u = points[1] - points[0], w = points[2] - points[0];
          EXPECT_LE(std::abs(cross(u, w)), 1e-7 * u.norm() * w.norm() + 1e-9 * lc * lc);
        } else if (points.size() == 2) {
          const Eigen::Vector2d u = points[1] - points[0];
          EXPECT_LE(std::abs(cross(u, directions[0])), 1e-7 * u.norm() + 1e-9 * lc);
        } else if (directions.size() == 2) {
          // Two pairs translating make the three angular velocities equal: the third pair too.
          ADD_FAILURE() << "two centres at infinity and one finite";
        }  // three at infinity: on the line at infinity
        ++triples;
      }
}

TEST(Explain, InstantCentresObeyKennedysTheorem) {
  int triples = 0;
  for (const char* name :
       {"watt-sixbar.yaml", "stephenson-sixbar.yaml", "fourbar-crank-rocker.yaml", "slider-crank-offset.yaml",
        "inverted-slider-crank-shaper.yaml", "scissor-lift.yaml", "five-bar.yaml", "machine-18.yaml",
        "compressor-myszka.yaml", "fourbar-drives-fourbar.yaml"}) {
    SCOPED_TRACE(name);
    const auto mech = example_mechanism(name);
    for (int step : {2, 7}) {
      ExplainOptions options;
      options.steps = 13;
      options.step = step;
      const Explanation ex = explain(mech, options);
      std::size_t links = 1;
      for (const InstantCentre& c : ex.centres)
        if (c.body_a == -1) ++links;
      EXPECT_EQ(ex.centres.size(), links * (links - 1) / 2);
      expect_kennedy(ex, triples);
    }
  }
  EXPECT_GT(triples, 500);
}

TEST(Explain, SlidersOnFixedGuidesHaveTheirCentreAtInfinityNormalToTheGuide) {
  const auto mech = example_mechanism("slider-crank-offset.yaml");
  const Model& m = mech->model();
  ASSERT_FALSE(m.sliders.empty());
  const Slider& s = m.sliders.front();
  const Eigen::Vector2d guide = (m.points[s.along[1]].position - m.points[s.along[0]].position).normalized();
  ExplainOptions options;
  options.steps = 13;
  options.step = 4;
  const Explanation ex = explain(mech, options);
  const InstantCentre& c = centre(ex, -1, s.body);
  ASSERT_TRUE(c.at_infinity);
  EXPECT_NEAR(std::abs(c.direction.dot(guide)), 0.0, 1e-12);
  EXPECT_NEAR(c.direction.norm(), 1.0, 1e-12);
}

TEST(Explain, DocumentsHaveNoNegativeZerosOrNoise) {
  const std::regex negative_zero(R"((^|[^0-9.eE])-0([^.0-9]|$))");
  const std::regex noise(R"([0-9]e-(1[6-9]|[2-9][0-9]|3[0-9][0-9]))");
  for (const char* name : {"fourbar-crank-rocker.yaml", "scissor-lift.yaml", "inverted-slider-crank-shaper.yaml"}) {
    const Explanation ex = explain(example_mechanism(name));
    for (ExplainFormat f : {ExplainFormat::Text, ExplainFormat::Markdown, ExplainFormat::Latex}) {
      const std::string doc = render_explanation(ex, f);
      EXPECT_FALSE(std::regex_search(doc, negative_zero)) << name;
      EXPECT_FALSE(std::regex_search(doc, std::regex(R"(\b(nan|inf)\b)"))) << name;
      std::smatch match;
      // Rounding noise (below 1e-15 of a quantity) is printed as 0; only residuals may be tiny.
      std::istringstream lines(doc);
      std::string line;
      while (std::getline(lines, line))
        if (line.find("Phi") == std::string::npos && line.find("Converged") == std::string::npos &&
            std::regex_search(line, match, noise) && std::isdigit(static_cast<unsigned char>(line[0])) == 0)
          ADD_FAILURE() << name << ": " << line;
    }
  }
}

TEST(Explain, TextSaysWhatTheCourseNotebooksWouldAsk) {
  const Explanation ex = explain(example_mechanism("fourbar-crank-rocker.yaml"),
                                 ExplainOptions{30, std::nullopt, 50, {}, kDefaultMaxSweepSamples});
  const std::string text = render_explanation(ex, ExplainFormat::Text);
  for (const char* expected : {"n = 4, PI = 4, PII = 0", "G = 3 (n - 1) - 2 PI - PII = 3 (4 - 1) - 2*4 - 0 = 1",
                               "q = [x_A, y_A, x_B, y_B, x_P, y_P]^T", "x_A^2 + y_A^2 - 80^2 = 0",
                               "(x_B - 200)^2 + y_B^2 - 150^2 = 0", "x_A*sin(th_crank) - y_A*cos(th_crank) = 0",
                               "th_crank(t) = 30 deg = 0.523599 rad", "no angle coordinates", "I(ground,coupler)"})
    EXPECT_NE(text.find(expected), std::string::npos) << expected;
  const std::string md = render_explanation(ex, ExplainFormat::Markdown);
  EXPECT_NE(md.find("$$x_{A}\\,\\sin \\theta_{\\mathrm{crank}} - y_{A}\\,\\cos \\theta_{\\mathrm{crank}} = 0$$"),
            std::string::npos);
  // No line of a Markdown table is wider than a phone's screen allows.
  std::istringstream lines(md);
  std::string line;
  while (std::getline(lines, line))
    if (!line.empty() && line[0] == '|') {
      EXPECT_LE(line.size(), 80u) << line;
    }
  const std::string tex = render_explanation(ex, ExplainFormat::Latex);
  EXPECT_NE(tex.find("\\begin{bmatrix}"), std::string::npos);
  EXPECT_EQ(tex.find("$$"), std::string::npos);
}

// Names are the user's: in LaTeX and Markdown they are literal text wherever they appear (the rows
// of the velocity table wrote "O_2" raw, which LaTeX cannot typeset).
TEST(Explain, NamesAreEscapedInEveryLatexAndMarkdownLine) {
  const std::string path = std::string(NBAR_EXAMPLES_DIR) + "/fourbar-crank-rocker.yaml";
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text = std::regex_replace(text, std::regex("\\bO2\\b"), "O_2");
  const auto mech = std::make_shared<const Mechanism>(io::parse_model(text, "renamed.yaml").model);
  const Explanation ex = explain(mech, ExplainOptions{30, std::nullopt, 50, {}, kDefaultMaxSweepSamples});
  const std::string tex = render_explanation(ex, ExplainFormat::Latex);
  const std::string md = render_explanation(ex, ExplainFormat::Markdown);
  EXPECT_NE(tex.find("1 length of crank (O\\_2-A) & $0$"), std::string::npos);
  EXPECT_NE(md.find("| 1 length of crank (O\\_2-A) | $0$ |"), std::string::npos);
  for (const std::string& doc : {tex, md}) {
    std::istringstream lines(doc);
    std::string line;
    while (std::getline(lines, line)) {
      // Outside maths (where the name is a subscript, O_{2}... written by latex_name) no bare "O_2".
      EXPECT_EQ(line.find(" O_2"), std::string::npos) << line;
      EXPECT_EQ(line.find("(O_2"), std::string::npos) << line;
    }
  }
}

void expect_no_null(const nlohmann::json& j, const std::string& where) {
  if (j.is_null()) ADD_FAILURE() << "null at " << where;
  if (j.is_number_float()) {
    EXPECT_TRUE(std::isfinite(j.get<double>())) << where;
  }
  if (j.is_object())
    for (auto it = j.begin(); it != j.end(); ++it) expect_no_null(it.value(), where + "." + it.key());
  if (j.is_array())
    for (std::size_t i = 0; i < j.size(); ++i) expect_no_null(j[i], where + "[" + std::to_string(i) + "]");
}

TEST(Explain, JsonCarriesEverySectionAndNeverNull) {
  for (const char* name : {"fourbar-crank-rocker.yaml", "scissor-lift.yaml", "parallelogram-redundant.yaml"}) {
    ExplainOptions options;
    options.steps = 13;
    options.step = 2;
    const Explanation ex = explain(example_mechanism(name), options);
    const nlohmann::json j = io::explanation_json(ex);
    expect_no_null(j, name);
    EXPECT_EQ(j["count"]["dof"], ex.count.dof);
    EXPECT_EQ(j["equations"].size(), ex.equations.size());
    EXPECT_EQ(j["newton"]["iterations"].size(), ex.newton.size());
    EXPECT_EQ(j["centres"].size(), ex.centres.size());
    EXPECT_EQ(j["velocity"]["solution"].size(), static_cast<std::size_t>(ex.q.size()));
    EXPECT_EQ(j["equations"][0]["text"], ex.equations[0].text);
    EXPECT_DOUBLE_EQ(j["acceleration"]["solution"][1].get<double>(), ex.acceleration.solution[1]);
  }
}

TEST(Explain, ErrorsHaveKinds) {
  const auto mech = example_mechanism("fourbar-crank-rocker.yaml");
  ExplainOptions options;
  options.step = 361;
  try {
    explain(mech, options);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::BadInput);
    EXPECT_NE(std::string(e.what()).find("0 to 360"), std::string::npos);
  }
  options.step = -1;
  EXPECT_THROW(explain(mech, options), Error);
  EXPECT_THROW(explain(nullptr), Error);
}

TEST(Explain, NewtonTraceRecordsNothingWithoutATraceAndTheSameSolveWithOne) {
  const auto mech = example_mechanism("fourbar-crank-rocker.yaml");
  State a(*mech), b(*mech);
  std::vector<Series> values{Series(1, 0.7)};
  set_drivers(*mech, a, values);
  set_drivers(*mech, b, values);
  NewtonTrace trace;
  const NewtonReport plain = solve_position(*mech, a);
  const NewtonReport traced = solve_position(*mech, b, 50, &trace);
  EXPECT_EQ(plain.iterations, traced.iterations);
  EXPECT_EQ(a.q, b.q);  // bit for bit: tracing changes nothing
  ASSERT_EQ(trace.iterates.size(), static_cast<std::size_t>(traced.iterations) + 1);
  EXPECT_EQ(trace.iterates.back().q, b.q);
  EXPECT_DOUBLE_EQ(trace.iterates.back().residual, traced.residual);
}

}  // namespace
}  // namespace nbar
