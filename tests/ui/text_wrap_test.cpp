// Word wrap at blanks only (ui/text_wrap.hpp), with a fixed-width font of 1 per character.
#include "ui/text_wrap.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <stdexcept>
#include <string>

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

/// A fixed-width measure that counts the characters it is given and gives up past `limit`:
/// wrapping must measure each character a bounded number of times (linear time).
struct CountingMeasure {
  size_t measured = 0, limit = 0;
  float operator()(std::string_view s) {
    measured += s.size();
    if (measured > limit) throw std::runtime_error("quadratic: measured too much");
    return static_cast<float>(s.size());
  }
};

TEST(TextWrap, AFiveMegabyteLineIsWrappedInLinearTime) {
  const size_t n = 5u << 20;
  const std::string word(n, 'x');
  CountingMeasure one_word{0, 3 * n};
  std::string wrapped;
  ASSERT_NO_THROW(wrapped = wrap_at_blanks(word, 80, std::ref(one_word)));
  EXPECT_EQ(wrapped.size(), n + (n - 1) / 80);  // 80 characters a line
  std::string words;
  while (words.size() < n) words += "0.019375 gamma-hi ";
  CountingMeasure many_words{0, 3 * words.size()};
  ASSERT_NO_THROW(wrapped = wrap_at_blanks(words, 60, std::ref(many_words)));
  EXPECT_LE(wrapped.find('\n'), 60u);
}

TEST(TextWrap, SplitsBetweenUtf8SequencesAndShortens) {
  // Two-byte characters measured one unit each: never cut inside one.
  const auto glyphs = [](std::string_view s) {
    float w = 0;
    for (const char c : s) w += (static_cast<unsigned char>(c) & 0xC0) != 0x80 ? 1.0f : 0.0f;
    return w;
  };
  EXPECT_EQ(wrap_at_blanks(u8"\u03B3\u03B3\u03B3", 2, glyphs), u8"\u03B3\u03B3\n\u03B3");
  EXPECT_EQ(shorten("short", 10), "short");
  EXPECT_EQ(shorten(u8"\u03B3\u03B3\u03B3", 5), u8"\u03B3\u03B3\u2026 (6 bytes in all)");
  EXPECT_LT(shorten(std::string(5u << 20, 'n'), kShownName).size(), kShownName + 40);
}

}  // namespace
}  // namespace dampbound::ui
