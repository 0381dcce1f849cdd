// nbar export --dxf from the command line: the file written, the pose, and the errors.
#include "apps/cli_support.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Core>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace nbar::cli_test {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class TempDir {
 public:
  TempDir() : dir_(fs::temp_directory_path() / ("nbar_export_" + std::to_string(::getpid()) + "_" + std::to_string(count_++))) {
    fs::create_directories(dir_);
  }
  ~TempDir() { fs::remove_all(dir_); }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }

 private:
  static inline int count_ = 0;
  fs::path dir_;
};

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The second VERTEX of the file's first POLYLINE (the crank's outline), checked to start the
// arc (bulge 1).
Eigen::Vector2d second_vertex(const std::string& dxf) {
  std::istringstream in(dxf);
  std::string code, value;
  int vertices = 0;
  Eigen::Vector2d v(NAN, NAN);
  double bulge = 0;
  while (std::getline(in, code) && std::getline(in, value)) {
    const int c = std::stoi(code);
    if (c == 0) {
      if (vertices == 2) break;
      if (value == "VERTEX") ++vertices;
    } else if (vertices == 2) {
      if (c == 10) v.x() = std::stod(value);
      if (c == 20) v.y() = std::stod(value);
      if (c == 42) bulge = std::stod(value);
    }
  }
  EXPECT_EQ(bulge, 1.0);
  return v;
}

const std::string kExample = std::string(NBAR_EXAMPLES_DIR) + "/fourbar-rounded-crank.yaml";

TEST(ExportCli, WritesTheDxfAsDrawnAndInAPose) {
  TempDir dir;
  const CliRun drawn = nbar("export " + kExample + " --dxf " + dir.file("drawn.dxf"));
  ASSERT_EQ(drawn.code, 0) << drawn.err;
  const std::string text = read(dir.file("drawn.dxf"));
  EXPECT_EQ(text.rfind("  0\nSECTION\n  2\nHEADER\n", 0), 0u);
  EXPECT_TRUE(text.ends_with("  0\nEOF\n"));
  for (const char* layer : {"\ncrank\n", "\ncoupler\n", "\nrocker\n"}) EXPECT_THAT(text, HasSubstr(layer));
  // The crank's arc-starting vertex (80, -10) and its bulge, as drawn.
  EXPECT_THAT(text, HasSubstr(" 10\n80\n 20\n-10\n 30\n0\n 42\n1\n"));

  const CliRun turned = nbar("export " + kExample + " --dxf " + dir.file("at90.dxf") + " --at 90");
  ASSERT_EQ(turned.code, 0) << turned.err;
  // A quarter turn about O2 takes the crank's second vertex (80, -10) to (10, 80), to the
  // pose's precision; its bulge stays.
  const Eigen::Vector2d v = second_vertex(read(dir.file("at90.dxf")));
  EXPECT_NEAR(v.x(), 10, 1e-9);
  EXPECT_NEAR(v.y(), 80, 1e-9);
  EXPECT_EQ(second_vertex(text), Eigen::Vector2d(80, -10));
}

TEST(ExportCli, Errors) {
  TempDir dir;
  const CliRun none = nbar("export " + std::string(NBAR_EXAMPLES_DIR) + "/fourbar-crank-rocker.yaml --dxf " +
                           dir.file("x.dxf"));
  EXPECT_EQ(none.code, 2);
  EXPECT_THAT(none.err, HasSubstr("there is nothing to cut"));
  EXPECT_EQ(nbar("export " + kExample).code, 2);  // --dxf is required
  EXPECT_EQ(nbar("export " + kExample + " --dxf /nonexistent-dir/x.dxf").code, 2);
}

}  // namespace
}  // namespace nbar::cli_test
