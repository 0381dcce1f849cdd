// The HTML report: self-contained, with the sections the model calls for, and it opens in a
// browser without errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "nbar/io/model_file.hpp"
#include "nbar/render/image_canvas.hpp"
#include "nbar/render/report.hpp"
#include "render/render_support.hpp"

namespace nbar::render {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

std::string report_of(const std::string& example, int steps) {
  const io::LoadedModel file = io::load_model_file(std::string(NBAR_EXAMPLES_DIR) + "/" + example);
  const auto mech = std::make_shared<const Mechanism>(file.model);
  const ModelSummary summary = summarize(*mech);
  AnalysisOptions o = report_analysis_options(summary);
  o.steps = steps;
  o.sections = 100;
  ReportOptions options;
  options.source = example;
  options.frames = 24;
  return html_report(analyse(mech, o), summary, options);
}

// Every URL in the page: only the SVG namespace (a name, never fetched) is allowed.
std::vector<std::string> urls(const std::string& html) {
  std::vector<std::string> found;
  const std::regex url(R"(https?://[^\s"'<>)&]+)");
  for (auto it = std::sregex_iterator(html.begin(), html.end(), url); it != std::sregex_iterator(); ++it)
    if (it->str() != "http://www.w3.org/2000/svg") found.push_back(it->str());
  return found;
}

TEST(Report, KinematicsOnlyModel) {
  const std::string html = report_of("fourbar-crank-rocker.yaml", 73);
  EXPECT_THAT(html, ::testing::StartsWith("<!DOCTYPE html>"));
  EXPECT_THAT(html, HasSubstr("name=\"viewport\""));
  for (const char* id : {"summary", "motion", "kinematics"}) EXPECT_THAT(html, HasSubstr(std::string("id=\"") + id));
  EXPECT_THAT(html, Not(HasSubstr("id=\"forces\"")));
  EXPECT_THAT(html, HasSubstr("crank-rocker"));                 // Grashof class
  EXPECT_THAT(html, HasSubstr("Paths of the coupler points"));  // P is a coupler point
  EXPECT_THAT(html, HasSubstr("Angular jerk"));
  EXPECT_THAT(urls(html), ::testing::IsEmpty());
  EXPECT_THAT(html, Not(HasSubstr("nan")));
}

TEST(Report, FramesOutOfRangeAreBadInput) {
  const io::LoadedModel file = io::load_model_file(std::string(NBAR_EXAMPLES_DIR) + "/fourbar-crank-rocker.yaml");
  const auto mech = std::make_shared<const Mechanism>(file.model);
  AnalysisOptions o;
  o.steps = 5;
  const Analysis analysis = analyse(mech, o);
  for (const int frames : {-3, 0, 1, kMaxReportFrames + 1}) {
    ReportOptions options;
    options.frames = frames;
    try {
      html_report(analysis, summarize(*mech), options);
      ADD_FAILURE() << frames << " frames were taken";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::BadInput) << e.what();
      EXPECT_THAT(e.what(), HasSubstr("2 to 1000 frames, not " + std::to_string(frames)));
    }
  }
}

TEST(Report, KineticsAndStressesWhenTheModelHasThem) {
  const std::string html = report_of("fourbar-steel-bars.yaml", 37);
  for (const char* id : {"summary", "motion", "kinematics", "forces", "stresses"})
    EXPECT_THAT(html, HasSubstr(std::string("id=\"") + id));
  EXPECT_THAT(html, HasSubstr("Driver efforts"));
  EXPECT_THAT(html, HasSubstr("O2.ground&gt;crank"));  // a joint force, escaped
  EXPECT_THAT(html, HasSubstr("id=\"markers\""));      // largest stresses marked on the drawing
  EXPECT_THAT(html, HasSubstr("Safety factor"));
  EXPECT_THAT(urls(html), ::testing::IsEmpty());
  EXPECT_THAT(html, Not(HasSubstr("nan")));
}

// Each link's largest stress is drawn in the pose where it occurs: one picture per link, its
// caption saying where, its marker and label on it.
TEST(Report, StressMarkersInThePoseOfEachMaximum) {
  const io::LoadedModel file = io::load_model_file(std::string(NBAR_EXAMPLES_DIR) + "/fourbar-steel-bars.yaml");
  const auto mech = std::make_shared<const Mechanism>(file.model);
  const ModelSummary summary = summarize(*mech);
  AnalysisOptions o = report_analysis_options(summary);
  o.steps = 37;
  o.sections = 100;
  const Analysis analysis = analyse(mech, o);
  ReportOptions options;
  options.frames = 12;
  const std::string html = html_report(analysis, summary, options);
  const std::string stresses = html.substr(html.find("id=\"stresses\""));
  ASSERT_EQ(analysis.stress->peaks.size(), 3u);
  std::size_t figures = 0, markers = 0;
  for (std::size_t i = stresses.find("<figure>"); i != std::string::npos; i = stresses.find("<figure>", i + 1))
    ++figures;
  for (std::size_t i = stresses.find("id=\"markers\""); i != std::string::npos;
       i = stresses.find("id=\"markers\"", i + 1))
    ++markers;
  EXPECT_EQ(figures, 3u);
  EXPECT_EQ(markers, 3u);  // one marker a picture
  for (const StressPeak& p : analysis.stress->peaks) {
    // The drawing of that pose: the crank at its angle at the peak's step (10 deg a step).
    char caption[128];
    std::snprintf(caption, sizeof caption, "%s: %.3g MPa at crank = %g deg", mech->model().bodies[p.body].name.c_str(),
                  p.at.von_mises / 1e6, 10.0 * p.step);
    EXPECT_THAT(stresses, HasSubstr(caption));
  }
  // Not all at the start: the maxima of this example are at 350 and 10 deg.
  EXPECT_TRUE(std::any_of(analysis.stress->peaks.begin(), analysis.stress->peaks.end(),
                          [](const StressPeak& p) { return p.step != 0; }));
}

// Opens the report in headless Chromium (installed by scripts/install-deps.sh): no script
// error, a page that is not blank, at phone width too.
TEST(Report, OpensInChromiumAtDesktopAndPhoneWidth) {
  REQUIRE_CHROMIUM(browser);
  std::string name = "nbar_report_";  // built by append: g++ 12 warns falsely on "literal" + string
  name += std::to_string(::getpid());
  const fs::path dir = fs::temp_directory_path() / name;
  fs::create_directories(dir);
  const fs::path page = dir / "report.html";
  std::ofstream(page) << report_of("crank-rocker-gravity-spring.yaml", 37);
  for (int width : {1000, 390}) {
    SCOPED_TRACE("width " + std::to_string(width));
    const std::string w = std::to_string(width);
    const fs::path shot = dir / ("shot" + w + ".png");
    std::string command = nbar::render::test_support::browser_command(browser, dir / ("profile" + w));
    command += " --hide-scrollbars --virtual-time-budget=2000 --window-size=";
    command += w;
    command += ",1600 --screenshot=";
    command += shot.string();
    command += " file://";
    command += page.string();
    command += " >/dev/null 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0);
    const ImageCanvas image = ImageCanvas::read_png(shot.string());
    EXPECT_EQ(image.width(), width);
    // Not blank: many distinct colours (text, tables, the drawing, the plots).
    std::set<std::uint32_t> colours;
    const std::uint8_t* data = image.data();
    for (int y = 0; y < image.height(); y += 3)
      for (int x = 0; x < image.width(); x += 3) {
        const std::uint8_t* p = data + y * image.stride() + 4 * x;
        colours.insert(p[0] | p[1] << 8 | p[2] << 16);
      }
    EXPECT_GT(colours.size(), 50u);
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace nbar::render
