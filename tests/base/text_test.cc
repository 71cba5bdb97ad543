#include "common/base/text.h"

#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

#include <gtest/gtest.h>

namespace animat {
namespace {

TEST(TextTest, ShortestDoubleIsShortAndReadsBack) {
  EXPECT_EQ(ShortestDouble(0.7), "0.7");
  EXPECT_EQ(ShortestDouble(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(ShortestDouble(0), "0");
  EXPECT_EQ(ShortestDouble(-2.5), "-2.5");
  EXPECT_EQ(ShortestDouble(1e-6), "1e-06");
  EXPECT_EQ(ShortestDouble(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(ShortestDouble(std::nan("")), "nan");
  for (double v : {0.7, 1.0 / 3.0, 6.02214076e23, 5e-324,
                   1.7976931348623157e308, 0.04976833334335129}) {
    EXPECT_EQ(std::strtod(ShortestDouble(v).c_str(), nullptr), v) << v;
  }
}

TEST(TextTest, AsciiLowerCaseLowersOnlyAsciiCapitals) {
  EXPECT_EQ(AsciiLowerCase("NUMERICAL_FAILURE"), "numerical_failure");
  EXPECT_EQ(AsciiLowerCase("Avx512"), "avx512");
  EXPECT_EQ(AsciiLowerCase(""), "");
  EXPECT_EQ(AsciiLowerCase("\xc3\x89t\xc3\xa9"), "\xc3\x89t\xc3\xa9");
}

TEST(TextTest, ExcerptEscapesAndCuts) {
  EXPECT_EQ(Excerpt("abc"), "abc");
  EXPECT_EQ(Excerpt("a\"b\\c\n\t\r\x01\xff"), "a\\\"b\\\\c\\n\\t\\r\\x01\\xff");
  const std::string big(1000, 'x');
  EXPECT_EQ(Excerpt(big, 4), "xxxx... (1000 bytes)");
  EXPECT_EQ(Excerpt("abcd", 4), "abcd");
}

TEST(TextTest, ForeignTextKeepsQuotesAndCuts) {
  EXPECT_EQ(ForeignText("Expected \"}\".\n\x07"), "Expected \"}\".\\n\\x07");
  std::string big = "error: " + std::string(10000, '\0');
  const std::string out = ForeignText(big, 20);
  EXPECT_EQ(out,
            "error: \\x00\\x00\\x00\\x00\\x00\\x00\\x00\\x00\\x00\\x00\\x00"
            "\\x00\\x00...");
}

}  // namespace
}  // namespace animat
