// TableStream hands out result_table's rows one at a time without keeping the sweep: the same
// columns and, bit for bit, the same numbers (noise made 0 included), with or without the
// dynamics columns, whole or selected, from rows kept by its first pass or from a second pass;
// and its CSV is write_csv's, byte for byte.
#include "example_models.hpp"

#include <gtest/gtest.h>

#include <cctype>
#include <cstring>
#include <memory>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "nbar/analysis/analysis.hpp"
#include "nbar/analysis/table_stream.hpp"
#include "nbar/io/model_file.hpp"
#include "nbar/io/results_writer.hpp"

namespace nbar {
namespace {

using test_support::example_mechanism;

std::vector<std::vector<double>> streamed_rows(TableStream& stream) {
  std::vector<std::vector<double>> rows;
  stream.rows([&](const double* row) { rows.emplace_back(row, row + stream.columns().size()); });
  return rows;
}

// Bit for bit, so that -0 against 0 would count.
bool same_bits(const std::vector<std::vector<double>>& a, const std::vector<std::vector<double>>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t r = 0; r < a.size(); ++r)
    if (a[r].size() != b[r].size() || std::memcmp(a[r].data(), b[r].data(), a[r].size() * sizeof(double)) != 0)
      return false;
  return true;
}

struct Case {
  const char* model;
  bool dynamics;
  int order;
};

// gtest would print a Case as its bytes, a pointer among them, into every test's name in ctest.
void PrintTo(const Case& c, std::ostream* out) {
  *out << c.model << (c.dynamics ? " with dynamics" : "") << ", order " << c.order;
}

std::string case_name(const ::testing::TestParamInfo<Case>& info) {
  std::string name = info.param.model;
  name = name.substr(0, name.find('.'));
  for (char& ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return name + (info.param.dynamics ? "_dynamics" : "") + "_order" + std::to_string(info.param.order);
}

class TableStreamTest : public ::testing::TestWithParam<Case> {};

TEST_P(TableStreamTest, RowsAreResultTableBitForBit) {
  const Case c = GetParam();
  const auto mech = example_mechanism(c.model);
  AnalysisOptions options;
  options.steps = 541;
  options.order = c.order;
  options.dynamics = c.dynamics;
  const Analysis analysis = analyse(mech, options);
  const ResultTable table = result_table(analysis);

  // The rows kept by the first pass (541 rows fit the default budget), none kept (budget 0),
  // and a budget that runs out part way: one pass, then two.
  for (const std::size_t budget : {std::size_t{4} << 20, std::size_t{0}, std::size_t{5000}}) {
    SCOPED_TRACE("kept rows budget " + std::to_string(budget));
    TableStream stream(mech, options);
    stream.set_kept_rows_budget(budget);
    EXPECT_EQ(stream.columns(), table.columns);
    EXPECT_EQ(stream.units(), table.units);
    EXPECT_TRUE(same_bits(streamed_rows(stream), table.rows));
    EXPECT_EQ(stream.passes(), budget > 5000 ? 1 : 2);
    EXPECT_EQ(stream.sweep().solved, analysis.sweep.samples.size());
    EXPECT_TRUE(stream.sweep().samples.empty());  // no samples kept
    EXPECT_EQ(stream.sweep().complete, analysis.sweep.complete);
    EXPECT_EQ(stream.warnings().size(), analysis.warnings().size());
  }

  std::ostringstream buffered, streamed;
  io::write_csv(buffered, table);
  {
    TableStream again(mech, options);
    io::CsvWriter csv(streamed, again.columns());
    again.rows([&](const double* row) { csv.row(row); });
  }
  EXPECT_EQ(streamed.str(), buffered.str());
}

TEST_P(TableStreamTest, SelectedColumnsAreSelectColumnsOfTheWholeTable) {
  const Case c = GetParam();
  const auto mech = example_mechanism(c.model);
  AnalysisOptions options;
  options.steps = 97;
  options.order = c.order;
  options.dynamics = c.dynamics;
  const std::vector<std::string> patterns{"*.v*", "t", "*.angle"};
  const ResultTable table = select_columns(result_table(analyse(mech, options)), patterns);
  TableStream stream(mech, options);
  stream.select(patterns);
  EXPECT_EQ(stream.columns(), table.columns);
  EXPECT_TRUE(same_bits(streamed_rows(stream), table.rows));
}

INSTANTIATE_TEST_SUITE_P(Examples, TableStreamTest,
                         ::testing::Values(Case{"fourbar-crank-rocker.yaml", false, 2},
                                           Case{"fourbar-crank-rocker.yaml", true, 5},
                                           Case{"slider-crank-offset.yaml", true, 3}, Case{"machine-18.yaml", true, 2},
                                           Case{"fourbar-double-rocker.yaml", false, 2},  // stops early
                                           Case{"compressor-myszka-kinetics.yaml", true, 2},
                                           Case{"parallelogram-redundant.yaml", true, 2}),
                         case_name);

TEST(TableStream, RefusesStresses) {
  AnalysisOptions options;
  options.stress = true;
  EXPECT_THROW(TableStream(example_mechanism("fourbar-steel-bars.yaml"), options), Error);
}

}  // namespace
}  // namespace nbar
