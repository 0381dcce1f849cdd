// Golden-output test of the nbar command line: every case of tests/golden/cases.txt is run from
// the repository root, and its exit code, standard output, standard error and every file it
// writes under $OUT must equal, byte for byte, the files under tests/golden/expected/ that
// scripts/update-goldens.sh recorded (from the binary built before a refactor). Each case is
// one test, GoldenCases/Golden.Output/<case>.
//
// A case runs as `cd REPO && NBAR ARGS </dev/null` under /bin/sh, with every `$OUT` in ARGS
// replaced by a fresh temporary directory; in the outputs that directory's path is written
// back as `$OUT` and the binary's path as `nbar` (scripts/update-goldens.sh does the same).
#include <gtest/gtest.h>
#include <stdlib.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "apps/cli_support.hpp"

namespace {

namespace fs = std::filesystem;

const fs::path kSourceDir = NBAR_SOURCE_DIR;
const fs::path kCasesFile = kSourceDir / "tests" / "golden" / "cases.txt";
const fs::path kExpectedDir = kSourceDir / "tests" / "golden" / "expected";

struct GoldenCase {
  std::string name;
  std::string args;  // as written, with $OUT
  int line = 0;      // in cases.txt
};

// What ctest shows after the test's name: the arguments without the characters (quotes, globs,
// $) that the test names gtest_discover_tests makes would need escaped.
void PrintTo(const GoldenCase& c, std::ostream* os) {
  *os << "nbar";
  if (!c.args.empty()) *os << ' ';
  for (const char ch : c.args)
    if ((ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') ||
        std::string_view(" ._/,:=+-").find(ch) != std::string_view::npos)
      *os << ch;
}

bool valid_name(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
  });
}

// Every line of cases.txt that is not blank or a comment, as written (CasesFile checks them).
std::vector<GoldenCase> read_case_lines() {
  std::vector<GoldenCase> cases;
  std::ifstream in(kCasesFile);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    GoldenCase c;
    const auto space = line.find(' ');
    c.name = line.substr(0, space);
    c.args = space == std::string::npos ? "" : line.substr(space + 1);
    c.line = number;
    cases.push_back(c);
  }
  return cases;
}

// The cases to instantiate: those with a valid, not yet seen name.
std::vector<GoldenCase> load_cases() {
  std::vector<GoldenCase> cases;
  std::set<std::string> seen;
  for (const auto& c : read_case_lines())
    if (valid_name(c.name) && seen.insert(c.name).second) cases.push_back(c);
  return cases;
}

std::optional<std::string> read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void replace_all(std::string& s, const std::string& from, const std::string& to) {
  if (from.empty()) return;
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
    s.replace(at, from.size(), to);
}

// Every regular file under DIR, by its path relative to DIR ('/'-separated), sorted.
std::vector<std::string> files_under(const fs::path& dir) {
  std::vector<std::string> files;
  if (!fs::is_directory(dir)) return files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (!e.is_directory()) files.push_back(fs::relative(e.path(), dir).generic_string());
  std::sort(files.begin(), files.end());
  return files;
}

std::string shorten(const std::string& s, std::size_t from) {
  constexpr std::size_t kWidth = 200;
  const std::size_t start = from > kWidth / 2 ? from - kWidth / 2 : 0;
  std::string out = start > 0 ? "..." : "";
  out += s.substr(start, kWidth);
  if (start + kWidth < s.size()) out += "...";
  return out;
}

// Where EXPECTED and ACTUAL first differ: the line number and both lines.
std::string first_difference(const std::string& expected, const std::string& actual) {
  std::size_t at = 0;
  while (at < expected.size() && at < actual.size() && expected[at] == actual[at]) ++at;
  const std::size_t line_start = at == 0 ? 0 : [&] {
    const auto nl = expected.rfind('\n', at - 1);
    return nl == std::string::npos ? std::size_t{0} : nl + 1;
  }();
  const std::size_t line =
      static_cast<std::size_t>(std::count(expected.begin(), expected.begin() + static_cast<long>(line_start), '\n')) +
      1;
  auto line_of = [&](const std::string& s) -> std::string {
    if (line_start >= s.size()) return "<end of file>";
    const auto end = s.find('\n', line_start);
    return s.substr(line_start, end == std::string::npos ? std::string::npos : end - line_start);
  };
  const std::size_t column = at - line_start;
  std::ostringstream os;
  os << "first difference at line " << line << ", column " << column + 1 << " (byte " << at << "; sizes: expected "
     << expected.size() << ", actual " << actual.size() << ")\n"
     << "    expected: " << shorten(line_of(expected), column) << "\n"
     << "    actual:   " << shorten(line_of(actual), column);
  return os.str();
}

class Golden : public ::testing::TestWithParam<GoldenCase> {};

TEST_P(Golden, Output) {
  const GoldenCase& c = GetParam();
  ::setenv("COLUMNS", "80", 1);  // text tables wrap to the terminal's width: pin it, as update-goldens.sh does
  ::unsetenv("NBAR_LANG");  // English unless a case asks with --lang, as update-goldens.sh does
  std::string dir_template = (fs::temp_directory_path() / "nbar-golden.XXXXXX").string();
  ASSERT_NE(::mkdtemp(dir_template.data()), nullptr) << "cannot make a temporary directory";
  const fs::path out_dir = dir_template;
  const std::string out = out_dir.string();
  const std::string binary = NBAR_CLI_PATH;

  std::string args = c.args;
  replace_all(args, "$OUT", out);
  const nbar::cli_test::CliRun run =
      nbar::cli_test::run_shell("cd '" + kSourceDir.string() + "' && '" + binary + "' " + args + " </dev/null");
  auto normalise = [&](std::string s) {
    replace_all(s, out, "$OUT");
    replace_all(s, binary, "nbar");
    return s;
  };

  // What differs, in order: the exit code, stdout, stderr, the set of files, their contents.
  std::vector<std::string> differences;
  std::string detail;  // of the first difference
  auto compare = [&](const std::string& what, const std::optional<std::string>& expected, const std::string& actual) {
    if (!expected) {
      differences.push_back(what + ": the expected file is missing");
      if (detail.empty()) detail = differences.back();
    } else if (*expected != actual) {
      differences.push_back(what);
      if (detail.empty()) detail = what + ": " + first_difference(*expected, actual);
    }
  };
  const fs::path expected_base = kExpectedDir / c.name;
  compare("exit code", read_file(fs::path(expected_base.string() + ".code")), std::to_string(run.code) + "\n");
  compare("stdout", read_file(fs::path(expected_base.string() + ".stdout")), normalise(run.out));
  compare("stderr", read_file(fs::path(expected_base.string() + ".stderr")), normalise(run.err));

  const fs::path expected_files_dir = expected_base.string() + ".files";
  const std::vector<std::string> expected_files = files_under(expected_files_dir);
  const std::vector<std::string> actual_files = files_under(out_dir);
  for (const auto& f : expected_files)
    if (!std::binary_search(actual_files.begin(), actual_files.end(), f)) {
      differences.push_back("$OUT/" + f + ": expected but not written");
      if (detail.empty()) detail = differences.back();
    }
  for (const auto& f : actual_files) {
    if (!std::binary_search(expected_files.begin(), expected_files.end(), f)) {
      differences.push_back("$OUT/" + f + ": written but not expected");
      if (detail.empty()) detail = differences.back();
      continue;
    }
    compare("$OUT/" + f, read_file(expected_files_dir / f), normalise(read_file(out_dir / f).value_or("")));
  }
  fs::remove_all(out_dir);

  if (!differences.empty()) {
    std::ostringstream os;
    os << "golden case '" << c.name << "' (tests/golden/cases.txt line " << c.line
       << ") differs from tests/golden/expected/" << c.name << ".*\n"
       << "  command: cd " << kSourceDir.string() << " && nbar " << c.args << "\n"
       << "  " << detail << "\n";
    if (differences.size() > 1) {
      os << "  also differing:";
      for (std::size_t i = 1; i < differences.size(); ++i) os << (i > 1 ? ", " : " ") << differences[i];
      os << "\n";
    }
    os << "  If (and only if) the new output is intended, regenerate the expected files from the binary\n"
       << "  the goldens pin (normally the one built before the refactor):\n"
       << "    scripts/update-goldens.sh BASELINE_NBAR " << c.name << "\n"
       << "  (this run's binary: scripts/update-goldens.sh " << binary << " " << c.name << ")";
    ADD_FAILURE() << os.str();
  }
}

INSTANTIATE_TEST_SUITE_P(GoldenCases, Golden, ::testing::ValuesIn(load_cases()),
                         [](const ::testing::TestParamInfo<GoldenCase>& info) { return info.param.name; });
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(Golden);

// The cases file itself: readable, valid unique names, and no expected files left over from
// cases that are gone.
TEST(GoldenCasesFile, NamesAreValidUniqueAndEveryExpectedFileBelongsToACase) {
  ASSERT_TRUE(fs::exists(kCasesFile)) << kCasesFile;
  const std::vector<GoldenCase> lines = read_case_lines();
  EXPECT_FALSE(lines.empty()) << kCasesFile << " has no cases";
  std::set<std::string> names;
  for (const auto& c : lines) {
    EXPECT_TRUE(valid_name(c.name)) << "cases.txt line " << c.line << ": bad case name '" << c.name
                                    << "' (letters, digits and underscores only)";
    EXPECT_TRUE(names.insert(c.name).second) << "cases.txt line " << c.line << ": duplicate case '" << c.name << "'";
  }
  for (const auto& e : fs::directory_iterator(kExpectedDir)) {
    const std::string file = e.path().filename().string();
    const auto dot = file.rfind('.');
    const std::string stem = file.substr(0, dot);
    const std::string ext = dot == std::string::npos ? "" : file.substr(dot);
    EXPECT_TRUE(names.count(stem) && (ext == ".code" || ext == ".stdout" || ext == ".stderr" || ext == ".files"))
        << "tests/golden/expected/" << file << " belongs to no case of cases.txt (run scripts/update-goldens.sh)";
  }
}

}  // namespace
