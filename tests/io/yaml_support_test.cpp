// The readers' shared helpers: the typo distance (against the textbook full-matrix recursion,
// and its cut-off) and the UTF-8 check (against hand-made byte sequences).
#include "io/yaml_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <random>
#include <string>
#include <vector>

namespace nbar::io::yaml {
namespace {

// Optimal string alignment distance over the whole (n+1) x (m+1) table, ignoring case.
int reference_distance(const std::string& a, const std::string& b) {
  const auto same = [](char x, char y) { return std::tolower(x) == std::tolower(y); };
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<int>> d(n + 1, std::vector<int>(m + 1));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = static_cast<int>(i);
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = static_cast<int>(j);
  for (std::size_t i = 1; i <= n; ++i)
    for (std::size_t j = 1; j <= m; ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (same(a[i - 1], b[j - 1]) ? 0 : 1)});
      if (i > 1 && j > 1 && same(a[i - 1], b[j - 2]) && same(a[i - 2], b[j - 1]))
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[n][m];
}

TEST(EditDistance, KnownPairs) {
  EXPECT_EQ(edit_distance("O2", "o2"), 0);
  EXPECT_EQ(edit_distance("coupler", "copuler"), 1);  // one transposition
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3);
  EXPECT_EQ(edit_distance("", "abc"), 3);
  EXPECT_EQ(edit_distance("ca", "abc"), 3);  // OSA, not Damerau: no edit of a transposed pair
}

TEST(EditDistance, AgreesWithTheFullTableOnRandomNamesAndCutsOffAboveTheLimit) {
  std::mt19937 rng(16);
  std::uniform_int_distribution<int> length(0, 12), letter(0, 3);
  for (int trial = 0; trial < 3000; ++trial) {
    std::string a(static_cast<std::size_t>(length(rng)), 'a'), b(static_cast<std::size_t>(length(rng)), 'a');
    for (char& c : a) c = static_cast<char>("abAB"[letter(rng)]);
    for (char& c : b) c = static_cast<char>("abAB"[letter(rng)]);
    const int exact = reference_distance(a, b);
    ASSERT_EQ(edit_distance(a, b), exact) << a << " / " << b;
    for (int cutoff : {0, 1, 2, 4}) {
      const int cut = edit_distance(a, b, cutoff);
      if (exact <= cutoff)
        ASSERT_EQ(cut, exact) << a << " / " << b << " cutoff " << cutoff;
      else
        ASSERT_EQ(cut, cutoff + 1) << a << " / " << b << " cutoff " << cutoff;
    }
  }
}

TEST(EditDistance, LongNamesNeedNoTable) {
  // 20 000 characters each (issue 16: 1.57 GB with the full table): the cut-off ends it.
  const std::string a(20000, 'P'), b(20000, 'Q');
  EXPECT_EQ(edit_distance(a, b, 5), 6);
  EXPECT_FALSE(suggestion(a, std::vector<std::string>{b}));
}

TEST(Utf8, ValidTextPasses) {
  EXPECT_FALSE(first_invalid_utf8("plain ASCII"));
  EXPECT_FALSE(first_invalid_utf8("Mecanismo de cuatro barras: \xC3\xB1, \xE2\x82\xAC, \xF0\x9F\x98\x80"));
}

TEST(Utf8, TheFirstBadByteIsFound) {
  EXPECT_EQ(first_invalid_utf8("A\xff"), 1u);
  EXPECT_EQ(first_invalid_utf8("ab\xC3"), 2u);            // cut short
  EXPECT_EQ(first_invalid_utf8("\xC0\xAF"), 0u);          // overlong '/'
  EXPECT_EQ(first_invalid_utf8("x\xE0\x80\xAF"), 1u);     // overlong, three bytes
  EXPECT_EQ(first_invalid_utf8("\xED\xA0\x80"), 0u);      // a UTF-16 surrogate
  EXPECT_EQ(first_invalid_utf8("\xF4\x90\x80\x80"), 0u);  // past U+10FFFF
  EXPECT_EQ(first_invalid_utf8("\xE2\x82\xAC\x80"), 3u);  // a stray continuation byte
  EXPECT_EQ(utf8_character_length("\xE2\x82\xAC", 0), 3u);
}

}  // namespace
}  // namespace nbar::io::yaml
