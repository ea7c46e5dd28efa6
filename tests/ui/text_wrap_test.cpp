// Word wrap at blanks only (ui/text_wrap.hpp), with a fixed-width font of 1 per character.
#include "ui/text_wrap.hpp"

#include <gtest/gtest.h>

namespace dampbound::ui {
namespace {

float chars(std::string_view s) { return static_cast<float>(s.size()); }

TEST(TextWrap, BreaksAtBlanksNeverInsideANumber) {
  // ImGui's own wrap would break after "0." here; a number stays whole.
  const std::string text = "gamma_i = 0.002 <= gamma_hi = 0.019375619 (worst node 593)";
  EXPECT_EQ(wrap_at_blanks(text, 22, chars),
            "gamma_i = 0.002 <=\ngamma_hi = 0.019375619\n(worst node 593)");
  // Every line fits, and joining the lines with blanks gives the text back.
  const std::string wrapped = wrap_at_blanks(text, 12, chars);
  std::string joined;
  size_t start = 0;
  while (start <= wrapped.size()) {
    const size_t nl = std::min(wrapped.find('\n', start), wrapped.size());
    const std::string line = wrapped.substr(start, nl - start);
    EXPECT_LE(line.size(), 12u) << line;
    joined += (joined.empty() ? "" : " ") + line;
    start = nl + 1;
  }
  EXPECT_EQ(joined, text);
}

TEST(TextWrap, OnlyAWordWiderThanTheLineIsSplit) {
  // After its last '-' that fits, else where it must.
  EXPECT_EQ(wrap_at_blanks("exact dt limit (semi-implicit-euler)", 16, chars),
            "exact dt limit\n(semi-implicit-\neuler)");
  EXPECT_EQ(wrap_at_blanks("a 0.0123456789 b", 4, chars), "a\n0.01\n2345\n6789\nb");
  EXPECT_EQ(wrap_at_blanks("0.0123456789", 6, chars), "0.0123\n456789");
  EXPECT_EQ(wrap_at_blanks("abc", 0, chars), "a\nb\nc");  // at least a character a line
}

TEST(TextWrap, KeepsItsOwnBreaksAndShortText) {
  EXPECT_EQ(wrap_at_blanks("", 10, chars), "");
  EXPECT_EQ(wrap_at_blanks("fits on one", 11, chars), "fits on one");
  EXPECT_EQ(wrap_at_blanks("one\ntwo three four", 9, chars), "one\ntwo three\nfour");
  EXPECT_EQ(wrap_at_blanks("  lead", 10, chars), "  lead");  // leading blanks kept
  EXPECT_EQ(wrap_at_blanks("a   b", 2, chars), "a\nb");       // a run of blanks at a break dropped
}

}  // namespace
}  // namespace dampbound::ui
