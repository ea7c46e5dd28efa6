#include "core/io/format.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace dampbound {
namespace {

TEST(Format, ShortestRoundTripAndNoNaN) {
  EXPECT_EQ(format_number(0.05), "0.05");
  EXPECT_EQ(format_number(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(format_number(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(format_number(std::nan("")), "inf");
  EXPECT_EQ(json_number(std::nan("")), "null");
  EXPECT_EQ(json_string("a\"b\n"), "\"a\\\"b\\n\"");
}

TEST(Format, SignificantDigitsForPeople) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(format_digits(0.039804692345, 8), "0.039804692");
  EXPECT_EQ(format_digits(7.812324912, 4), "7.812");
  EXPECT_EQ(format_digits(1.5e-7, 8), "1.5e-07");
  EXPECT_EQ(format_digits(inf, 8), "inf");
  EXPECT_EQ(format_digits(-inf, 4), "-inf");
  EXPECT_EQ(format_digits(std::nan(""), 8), "n/a");
  EXPECT_EQ(format_digits(std::nan(""), 4, "-"), "-");
}

TEST(Printable, ControlCharactersAreEscaped) {
  EXPECT_EQ(printable("a\nb\x1b[31m\x7f"), "a\\x0ab\\x1b[31m\\x7f");
  EXPECT_EQ(printable("plain é"), "plain é");
}

}  // namespace
}  // namespace dampbound
