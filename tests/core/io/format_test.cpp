#include "core/io/format.hpp"

#include <gtest/gtest.h>

#include <clocale>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "core/io/scene_file.hpp"
#include "core/sweep/journal.hpp"
#include "tests/core/test_util.hpp"

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

/// LC_NUMERIC set to a locale with a decimal comma while it lives, as a host program's
/// setlocale(LC_ALL, "") would in Germany; the previous setting comes back after.
class CommaLocale {
 public:
  CommaLocale() : previous_(std::setlocale(LC_NUMERIC, nullptr)) {
    for (const char* name : {"de_DE.UTF-8", "de_DE.utf8", "fr_FR.UTF-8", "fr_FR.utf8"})
      if (std::setlocale(LC_NUMERIC, name)) return;
  }
  ~CommaLocale() { std::setlocale(LC_NUMERIC, previous_.c_str()); }
  CommaLocale(const CommaLocale&) = delete;
  CommaLocale& operator=(const CommaLocale&) = delete;

 private:
  std::string previous_;
};

TEST(Format, NumbersKeepTheirPointUnderACommaLocale) {
  const CommaLocale comma;
  char probe[16];
  std::snprintf(probe, sizeof probe, "%g", 0.5);
  ASSERT_STREQ(probe, "0,5") << "no locale with a decimal comma is installed: "
                                "scripts/install-deps.sh makes de_DE.UTF-8";
  EXPECT_EQ(format_number(0.57), "0.57");
  EXPECT_EQ(format_digits(0.039804692345, 8), "0.039804692");
  EXPECT_EQ(json_number(-2.5e-7), "-2.5e-07");
  char buf[32];
  c_snprintf(buf, sizeof buf, "%.1f%%", 12.5);
  EXPECT_STREQ(buf, "12.5%");
  char* end = nullptr;
  const char* text = "0.57 rest";
  EXPECT_EQ(c_strtod(text, &end), 0.57);
  EXPECT_EQ(end, text + 4);
  // A sweep journal's time line reads back.
  const JournalTime t{2, 12.5, 30.25, 7};
  std::string line = journal_time_line(t);
  line.pop_back();  // read without its newline, as the journal's reader does
  EXPECT_NE(line.find(" 12.500 30.250 "), std::string::npos) << line;
  const auto back = parse_journal_time_line(line);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->wall_s, 12.5);
  EXPECT_EQ(back->cpu_s, 30.25);
  // A shipped scene with an OBJ mesh loads (its coordinates are "0.000000" and the like).
  const SceneSpec cap = load_scene(test::source_path("scenes/tissue-cap.toml"));
  EXPECT_EQ(cap.model.node_count(), 433);
  std::snprintf(probe, sizeof probe, "%g", 0.5);
  EXPECT_STREQ(probe, "0,5");  // the calling thread's own formatting is left as the host set it
}

TEST(FormatHumanRange, OneNumberWhereBothEndsReadAlike) {
  EXPECT_EQ(format_human_range(0.25, std::nextafter(0.25, 1.0)), "0.25");
  EXPECT_EQ(format_human_range(1, 1.41421356), "1..1.41421");
  EXPECT_EQ(format_human_range(0, 0), "0");
}

TEST(Format, XmlEscapeReplacesAmpersandAnglesAndQuotes) {
  EXPECT_EQ(xml_escape("a<b & \"c\">d'"), "a&lt;b &amp; &quot;c&quot;&gt;d'");
}

TEST(Plural, OneIsSingularEveryOtherCountPlural) {
  EXPECT_EQ(plural(1, "spring"), "1 spring");
  EXPECT_EQ(plural(0, "spring"), "0 springs");
  EXPECT_EQ(plural(2, "node"), "2 nodes");
  EXPECT_EQ(plural(-1, "node"), "-1 nodes");
  EXPECT_EQ(plural(3, "class"), "3 classes");
  EXPECT_EQ(plural(1, "class"), "1 class");
  EXPECT_EQ(plural(12, "patch"), "12 patches");
}

}  // namespace
}  // namespace dampbound
