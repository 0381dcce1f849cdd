// Every public entry point, given bad input, throws nbar::Error of the right kind and nothing
// else: the one exception type the documentation promises (diagnostics.hpp), which every
// front-end maps in one place. A std::exception that is not an nbar::Error fails the test.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <typeinfo>
#include <vector>

#include "nbar/analysis/analysis.hpp"
#include "nbar/analysis/explain.hpp"
#include "nbar/analysis/fe_tables.hpp"
#include "nbar/analysis/pose.hpp"
#include "nbar/io/calculix.hpp"
#include "nbar/io/dxf_reader.hpp"
#include "nbar/io/dxf_writer.hpp"
#include "nbar/io/fe_export.hpp"
#include "nbar/io/model_export.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/io/results_writer.hpp"
#include "nbar/io/sketch.hpp"
#include "nbar/io/synthesis_task.hpp"
#include "nbar/kinematics/mechanism.hpp"
#include "nbar/kinematics/table.hpp"
#include "nbar/model/curves.hpp"
#include "nbar/model/diagnostics.hpp"
#include "nbar/model/geometry.hpp"
#include "nbar/model/law.hpp"
#include "nbar/model/units.hpp"
#include "nbar/render/animation.hpp"
#include "nbar/render/drawing.hpp"
#include "nbar/render/image_canvas.hpp"
#include "nbar/render/pictures.hpp"
#include "nbar/render/plot.hpp"
#include "nbar/render/scene.hpp"
#include "nbar/stress/mesh.hpp"
#include "nbar/stress/plane_stress.hpp"
#include "nbar/stress/section.hpp"
#include "nbar/synthesis/five_point.hpp"
#include "nbar/synthesis/nine_point.hpp"
#include "nbar/synthesis/path_fit.hpp"
#include "nbar/synthesis/polynomial.hpp"
#include "nbar/synthesis/run.hpp"
#include "nbar/synthesis/solve.hpp"

namespace nbar {
namespace {

// Success only when `call` throws an nbar::Error of kind `expected`.
::testing::AssertionResult throws_error(ErrorKind expected, const std::function<void()>& call) {
  try {
    call();
  } catch (const Error& e) {
    if (e.kind() == expected) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "an nbar::Error of kind " << to_string(e.kind()) << " instead of "
                                         << to_string(expected) << ": " << e.what();
  } catch (const std::exception& e) {
    return ::testing::AssertionFailure() << "a " << typeid(e).name()
                                         << " that is not an nbar::Error left the library: " << e.what();
  } catch (...) {
    return ::testing::AssertionFailure() << "an exception that is not even a std::exception left the library";
  }
  return ::testing::AssertionFailure() << "nothing was thrown";
}

#define EXPECT_NBAR_ERROR(kind, ...) EXPECT_TRUE(throws_error(ErrorKind::kind, [&] { __VA_ARGS__; }))

const std::string kExamples = NBAR_EXAMPLES_DIR;

std::shared_ptr<const Mechanism> crank_rocker() {
  static const auto mechanism =
      std::make_shared<const Mechanism>(io::load_model_file(kExamples + "/fourbar-crank-rocker.yaml").model);
  return mechanism;
}

Analysis crank_rocker_sweep() {
  AnalysisOptions options;
  options.steps = 5;
  return analyse(crank_rocker(), options);
}

TEST(ErrorSweep, ModelParsing) {
  EXPECT_NBAR_ERROR(InvalidModel, io::parse_model("points: [", "broken.yaml"));
  EXPECT_NBAR_ERROR(InvalidModel, io::parse_model("points: {O: [0, 0]}\nbodies: {a: [O, Q]}\n", "unknown.yaml"));
  EXPECT_NBAR_ERROR(InvalidModel, io::parse_model(std::string(100000, '['), "deep.yaml"));
  EXPECT_NBAR_ERROR(InvalidModel, io::parse_model("name: \"\xff\xfe\"\n", "not-utf8.yaml"));
  EXPECT_NBAR_ERROR(InvalidModel, io::load_model_file("/nonexistent-nbar-dir/model.yaml"));
  const std::string driver = "drivers: [{angle: crank, from: 0, to: 360, law: \"sin(\"}]\n";
  EXPECT_NBAR_ERROR(
      InvalidModel,
      io::parse_model("points: {O: [0, 0], A: [1, 0]}\nground: [O]\nbodies: {crank: [O, A]}\n" + driver, "law.yaml"));
}

TEST(ErrorSweep, MechanismConstruction) {
  Model no_driver = crank_rocker()->model();
  no_driver.drivers.clear();
  EXPECT_NBAR_ERROR(InvalidModel, Mechanism mechanism(no_driver));
  Model nowhere = crank_rocker()->model();
  nowhere.points[0].position.x() = std::nan("");
  EXPECT_NBAR_ERROR(InvalidModel, Mechanism mechanism(nowhere));
}

TEST(ErrorSweep, AnalyseWithBadOptions) {
  AnalysisOptions order;
  order.order = 9;
  EXPECT_NBAR_ERROR(BadInput, analyse(crank_rocker(), order));
  AnalysisOptions steps;
  steps.steps = -1;
  EXPECT_NBAR_ERROR(BadInput, analyse(crank_rocker(), steps));
  AnalysisOptions too_many;
  too_many.steps = 1000;
  too_many.max_steps = 10;
  EXPECT_NBAR_ERROR(BadInput, analyse(crank_rocker(), too_many));
  AnalysisOptions sections;
  sections.stress = true;
  sections.sections = 1;
  EXPECT_NBAR_ERROR(BadInput, analyse(crank_rocker(), sections));
  const Analysis analysis = crank_rocker_sweep();
  EXPECT_NBAR_ERROR(BadInput, select_columns(result_table(analysis), {"no-such-column"}));
  EXPECT_NBAR_ERROR(BadInput, section_profile_table(analysis, 99, 0));
  // The finite-element field's tables and export need that stage: this sweep has none.
  EXPECT_NBAR_ERROR(BadInput, fe_points_table(analysis, 0, 0, {{0, 0}}, QueryFrame::body));
  EXPECT_NBAR_ERROR(BadInput, fe_line_table(analysis, 0, 0, {0, 0}, {1, 0}, 5, QueryFrame::model));
  EXPECT_NBAR_ERROR(BadInput, fe_hole_table(analysis, 0, 0, 0, QueryFrame::body));
  EXPECT_NBAR_ERROR(BadInput, fe_section_table(analysis, 0, 0, 5));
  std::ostringstream out;
  EXPECT_NBAR_ERROR(BadInput, io::write_fe_vtu(out, analysis, 0, 0));
  EXPECT_NBAR_ERROR(BadInput, io::write_fe_nodes_csv(out, analysis, 0, 0));
  EXPECT_NBAR_ERROR(BadInput, io::write_fe_elements_csv(out, analysis, 0));
}

TEST(ErrorSweep, PoseAndExplain) {
  EXPECT_NBAR_ERROR(BadInput, pose_at(*crank_rocker(), std::nan("")));
  EXPECT_NBAR_ERROR(BadInput, pose_at(*crank_rocker(), 0.0, 9));
  ExplainOptions past;
  past.step = 100000;
  EXPECT_NBAR_ERROR(BadInput, explain(crank_rocker(), past));
  ExplainOptions negative;
  negative.step = -1;
  EXPECT_NBAR_ERROR(BadInput, explain(crank_rocker(), negative));
}

TEST(ErrorSweep, SynthesisOfBadTasks) {
  using synthesis::SynthesisKind;
  using synthesis::SynthesisTask;
  SynthesisTask five;
  five.kind = SynthesisKind::FivePoint;
  five.file = "five.yaml";
  five.where = {3, 1};
  five.points = {{0, 0}, {1, 0}, {2, 1}, {3, 1}, {4, 0}};  // the pivots coincide (both at 0, 0)
  EXPECT_NBAR_ERROR(InvalidModel, synthesis::run_synthesis(five));
  try {
    synthesis::run_synthesis(five);
  } catch (const Error& e) {  // the solver's complaint is placed at the task
    EXPECT_EQ(e.file(), "five.yaml");
    EXPECT_EQ(e.mark().line, 3);
  }
  SynthesisTask nine;
  nine.kind = SynthesisKind::NinePoint;
  nine.points.assign(8, Eigen::Vector2d(1, 2));
  EXPECT_NBAR_ERROR(InvalidModel, synthesis::run_synthesis(nine));
  nine.points.assign(9, Eigen::Vector2d(1, 2));
  EXPECT_NBAR_ERROR(InvalidModel, synthesis::run_synthesis(nine));
  SynthesisTask path;
  path.kind = SynthesisKind::Path;
  for (int k = 0; k < 12; ++k) path.points.emplace_back(k, 2 * k);  // on one line
  EXPECT_NBAR_ERROR(InvalidModel, synthesis::run_synthesis(path));
  SynthesisTask burmester;
  burmester.kind = SynthesisKind::Burmester;
  burmester.poses = {{{0, 0}, 0}, {{0, 0}, 0}, {{0, 0}, 0}};
  EXPECT_NBAR_ERROR(InvalidModel, synthesis::run_synthesis(burmester));
  // The solvers called directly say the same.
  synthesis::FivePointTask coincident;
  EXPECT_NBAR_ERROR(InvalidModel, synthesis::solve_five_point(coincident));
  std::array<Eigen::Vector2d, 9> line;
  for (int k = 0; k < 9; ++k) line[static_cast<std::size_t>(k)] = Eigen::Vector2d(k, k);
  EXPECT_NBAR_ERROR(InvalidModel, synthesis::solve_nine_point(line));
}

TEST(ErrorSweep, TaskParsing) {
  EXPECT_NBAR_ERROR(InvalidModel, io::parse_synthesis_task("task: nonsense\n", "bad.yaml"));
  EXPECT_NBAR_ERROR(InvalidModel, io::parse_synthesis_task("task: [", "broken.yaml"));
  EXPECT_NBAR_ERROR(InvalidModel, io::parse_synthesis_task("task: function\nfunction: \"log(\"\n", "f.yaml"));
  EXPECT_NBAR_ERROR(InvalidModel, io::load_synthesis_task("/nonexistent-nbar-dir/task.yaml"));
}

Region square(double side) {
  Region r;
  r.outline = {{0, 0}, {side, 0}, {side, side}, {0, side}};
  return r;
}

TEST(ErrorSweep, PlatesMeshesAndFiniteElements) {
  Region degenerate;
  degenerate.outline = {{0, 0}, {1, 0}, {2, 0}};
  EXPECT_NBAR_ERROR(BadInput, check_region(degenerate));
  EXPECT_NBAR_ERROR(BadInput, fe::mesh_region(degenerate));
  fe::MeshOptions tiny;
  tiny.size = 1e-4;
  tiny.max_nodes = 50;
  EXPECT_NBAR_ERROR(BadInput, fe::mesh_region(square(1.0), tiny));
  EXPECT_NBAR_ERROR(BadInput, make_bar({0, 0}, {0, 0}, 0.01, 0.01, 0, 0));
  EXPECT_NBAR_ERROR(BadInput, section_intervals(square(1.0), {0, 0}, {0, 0}));

  fe::ElasticMaterial steel{200e9, 0.3, 0.005, 7850};
  EXPECT_NBAR_ERROR(BadInput, fe::PlateModel(fe::TriMesh{}, steel));
  fe::ElasticMaterial rubbery = steel;
  rubbery.poisson_ratio = 0.5;
  EXPECT_NBAR_ERROR(BadInput, fe::PlateModel(fe::mesh_region(square(1.0)), rubbery));
  const fe::PlateModel plate(fe::mesh_region(square(1.0)), steel);
  fe::LoadCase no_hole;
  no_hole.bearings.push_back({7, {1, 0}});
  EXPECT_NBAR_ERROR(BadInput, plate.solve(no_hole));
  fe::LoadCase outside;
  outside.forces.push_back({{5, 5}, {1, 0}});
  EXPECT_NBAR_ERROR(BadInput, plate.solve(outside));
}

TEST(ErrorSweep, CurvesAndLaws) {
  EXPECT_NBAR_ERROR(BadInput, CubicSpline({{0, 0}, {0, 0}, {1, 1}}, false));
  EXPECT_NBAR_ERROR(InvalidModel, Law::parse("sin("));
  EXPECT_NBAR_ERROR(InvalidModel, Law::parse(""));
  EXPECT_NBAR_ERROR(UndefinedLaw, Law::parse("log(t)").value(-1.0));
  EXPECT_NBAR_ERROR(UndefinedLaw, Law::parse("abs(t)").series(0.0, 3));
  EXPECT_NBAR_ERROR(BadInput, Law::parse("t").series(0.0, 0));
  EXPECT_NBAR_ERROR(BadInput, Law().value(0.0));
}

TEST(ErrorSweep, Units) {
  EXPECT_NBAR_ERROR(BadInput, parse_rate("fast", 1));
  EXPECT_NBAR_ERROR(BadInput, parse_rate("5 RPM", 1));
  EXPECT_NBAR_ERROR(BadInput, parse_rate("5 furlong/s", 1));
  EXPECT_NBAR_ERROR(BadInput, parse_rate("5 rad", 2));
  EXPECT_NBAR_ERROR(BadInput, parse_rate("1e999 rpm", 1));
}

TEST(ErrorSweep, Polynomials) {
  using synthesis::Polynomial;
  using synthesis::PolynomialSystem;
  EXPECT_NBAR_ERROR(BadInput, Polynomial::variable(2, 5));
  EXPECT_NBAR_ERROR(BadInput, PolynomialSystem(std::vector<Polynomial>{}));
  const Polynomial x = Polynomial::variable(2, 0), y = Polynomial::variable(2, 1);
  EXPECT_NBAR_ERROR(BadInput, PolynomialSystem({x, Polynomial::variable(3, 0)}));
  EXPECT_NBAR_ERROR(BadInput, x + Polynomial::variable(3, 0));
  EXPECT_NBAR_ERROR(BadInput, synthesis::solve_total_degree(PolynomialSystem({x * y - 1.0})));
  EXPECT_NBAR_ERROR(BadInput, synthesis::solve_linear_product(PolynomialSystem({x - 1.0, y - 1.0}), {{0}}));
}

TEST(ErrorSweep, PicturesAndPlots) {
  const Analysis analysis = crank_rocker_sweep();
  const Mechanism& mech = *analysis.mechanism;
  render::DrawOptions zero;
  zero.width = 0;
  const auto points = render::sample_points(mech, analysis.sweep.samples[0]);
  EXPECT_NBAR_ERROR(BadInput, render::drawing_png(mech, analysis.sweep, points, zero));
  render::ImageCanvas canvas(40, 30);
  EXPECT_NBAR_ERROR(BadInput, render::draw_sample(canvas, mech, analysis.sweep, 99, {}));
  EXPECT_NBAR_ERROR(BadInput, render::drawing_scene_json(mech, analysis.sweep, {}, 99));

  EXPECT_NBAR_ERROR(BadInput, render::nice_ticks(0, std::numeric_limits<double>::infinity()));
  render::PlotSpec spec;
  spec.x = {0, 1, 2};
  spec.series.push_back({"y", "m", {1, 2}});
  EXPECT_NBAR_ERROR(BadInput, render::draw_plot(canvas, spec));
  render::PlotSpec no_x;
  EXPECT_NBAR_ERROR(BadInput, render::set_plot_data(no_x, ResultTable{}, ResultTable{}));
}

TEST(ErrorSweep, Animations) {
  const Analysis analysis = crank_rocker_sweep();
  render::DrawOptions small;
  small.width = 60;
  small.height = 40;
  EXPECT_NBAR_ERROR(BadInput, render::Animation(analysis.mechanism, SweepResult{}, small));
  EXPECT_NBAR_ERROR(BadInput, render::Animation(analysis.mechanism, analysis.sweep, small, 3, 0.0));
  render::DrawOptions wide = small;
  wide.width = 70000;
  EXPECT_NBAR_ERROR(BadInput, render::Animation(analysis.mechanism, analysis.sweep, wide, 2).write_gif("/dev/null"));
  const render::Animation animation(analysis.mechanism, analysis.sweep, small, 2);
  EXPECT_NBAR_ERROR(Internal, animation.write_gif("/nonexistent-nbar-dir/a.gif"));
  EXPECT_NBAR_ERROR(Internal, animation.write_svg_animation("/nonexistent-nbar-dir/a.svg"));
  EXPECT_NBAR_ERROR(Internal, animation.write_html_animation("/nonexistent-nbar-dir/a.html"));
}

TEST(ErrorSweep, ImageCanvas) {
  EXPECT_NBAR_ERROR(BadInput, render::ImageCanvas(0, 10));
  EXPECT_NBAR_ERROR(BadInput, render::ImageCanvas(10, -1));
  EXPECT_NBAR_ERROR(Internal, render::ImageCanvas(100000, 100000));
  const render::ImageCanvas canvas(4, 4);
  EXPECT_NBAR_ERROR(BadInput, canvas.pixel(4, 0));
  EXPECT_NBAR_ERROR(Internal, canvas.write_png("/nonexistent-nbar-dir/a.png"));
  EXPECT_NBAR_ERROR(Internal, render::ImageCanvas::read_png("/nonexistent-nbar-dir/a.png"));
}

TEST(ErrorSweep, SketchReadersAndWriters) {
  EXPECT_NBAR_ERROR(InvalidModel, io::read_dxf_plate("0\nSECTION\n2\nENTITIES\n0\nNONSENSE\n", "bad.dxf", 1e-3));
  EXPECT_NBAR_ERROR(InvalidModel, io::read_dxf_plate("not a dxf", "bad.dxf", 1e-3));
  EXPECT_NBAR_ERROR(InvalidModel, io::read_sketch("<svg", "bad.svg", io::SketchFormat::kSvg));
  EXPECT_NBAR_ERROR(InvalidModel, io::read_sketch("<svg xmlns='http://www.w3.org/2000/svg'></svg>", "empty.svg",
                                                  io::SketchFormat::kSvg));
  EXPECT_NBAR_ERROR(InvalidModel, io::read_sketch("1, 2\n3\n", "bad.csv", io::SketchFormat::kCsv));
  // The crank-rocker has no plates to cut.
  const auto points = render::sample_points(*crank_rocker(), crank_rocker_sweep().sweep.samples[0]);
  EXPECT_NBAR_ERROR(BadInput, io::cutting_dxf(*crank_rocker(), points));
  EXPECT_NBAR_ERROR(BadInput, io::cutting_svg(*crank_rocker(), points));
}

TEST(ErrorSweep, CalculixResultsAndWriters) {
  std::istringstream bad(" -4  DISP        4    1\n -1         1 1.0000\n");
  EXPECT_NBAR_ERROR(BadInput, fe::read_calculix_frd(bad));
  std::istringstream garbled(" -4  DISP        4    1\n -1 nonsense!  1.00000E+00 2.00000E+00 3.00000E+00\n");
  EXPECT_NBAR_ERROR(BadInput, fe::read_calculix_frd(garbled));

  const Analysis analysis = crank_rocker_sweep();
  std::ostringstream out;
  EXPECT_NBAR_ERROR(BadInput, io::write_table(out, "xml", analysis, result_table(analysis)));
}

TEST(ErrorSweep, ModelExport) {
  // Only kinematic models can be written back as model files yet.
  const Model steel = io::load_model_file(kExamples + "/fourbar-steel-bars.yaml").model;
  EXPECT_NBAR_ERROR(BadInput, io::model_yaml(steel));
}

}  // namespace
}  // namespace nbar
