#include "ui/text_wrap.hpp"

#include <algorithm>
#include <string>

namespace dampbound::ui {

namespace {
bool blank(char c) {
  return c == ' ' || c == '\t';
}

/// The length in bytes of the UTF-8 sequence that starts with `lead` (1 for a stray byte).
size_t sequence_length(unsigned char lead) {
  if (lead < 0x80) return 1;
  if ((lead >> 5) == 0x6) return 2;
  if ((lead >> 4) == 0xE) return 3;
  if ((lead >> 3) == 0x1E) return 4;
  return 1;
}

/// The next character of `s` from byte `k` (whole UTF-8 sequences, clipped to the end).
size_t next_char(std::string_view s, size_t k) {
  return std::min(s.size(), k + sequence_length(static_cast<unsigned char>(s[k])));
}

/// Appends `word` (`word_w` wide) to `out`, whose current line is `line_w` wide: a word wider
/// than what is left is split over lines, after its last '-' or '/' that fits, else after as
/// many characters as fit (at least one). One pass over the word, each character measured
/// once. Returns the width of the last line.
float append_long_word(std::string& out, float line_w, std::string_view word, float word_w,
                       float width, const std::function<float(std::string_view)>& measure) {
  while (line_w + word_w > width && next_char(word, 0) < word.size()) {
    size_t fit = 0, dash = 0;  // bytes that fit; bytes up to the last '-' or '/' among them
    float fit_w = 0, dash_w = 0;
    for (size_t k = 0; k < word.size();) {
      const size_t next = next_char(word, k);
      const float w = measure(word.substr(k, next - k));
      if (fit > 0 && line_w + fit_w + w > width) break;
      fit = next;
      fit_w += w;
      if (next > 1 && (word[k] == '-' || word[k] == '/')) dash = next, dash_w = fit_w;
      k = next;
    }
    const bool at_dash = dash > 0;
    const size_t cut = at_dash ? dash : fit;
    const float cut_w = at_dash ? dash_w : fit_w;
    out.append(word.substr(0, cut));
    out += '\n';
    word.remove_prefix(cut);
    word_w -= cut_w;
    line_w = 0;
  }
  out.append(word);
  return line_w + word_w;
}
}  // namespace

std::string wrap_at_blanks(std::string_view text, float width,
                           const std::function<float(std::string_view)>& measure) {
  std::string out;
  out.reserve(text.size() + text.size() / 16);
  float line_w = 0;  // the width of the current line of `out`
  bool line_empty = true;
  size_t k = 0;
  while (k < text.size()) {
    if (text[k] == '\n') {
      out += '\n';
      line_w = 0;
      line_empty = true;
      ++k;
      continue;
    }
    // The blanks before the next word, and the word.
    size_t w = k;
    while (w < text.size() && blank(text[w])) ++w;
    size_t end = w;
    while (end < text.size() && !blank(text[end]) && text[end] != '\n') ++end;
    const std::string_view blanks = text.substr(k, w - k), word = text.substr(w, end - w);
    const float blanks_w = measure(blanks), word_w = measure(word);
    k = end;
    if (!line_empty && !word.empty() && line_w + blanks_w + word_w > width) {
      out += '\n';  // the word goes to a new line, its blanks are dropped
      line_w = append_long_word(out, 0, word, word_w, width, measure);
      continue;
    }
    out.append(blanks);
    if (line_empty) {
      line_w = append_long_word(out, blanks_w, word, word_w, width, measure);
    } else {
      out.append(word);
      line_w += blanks_w + word_w;
    }
    line_empty = out.empty() || out.back() == '\n';
  }
  return out;
}

std::string shorten(std::string_view text, size_t max_bytes) {
  if (text.size() <= max_bytes) return std::string(text);
  size_t cut = 0;
  while (cut < text.size()) {
    const size_t next = next_char(text, cut);
    if (next > max_bytes) break;
    cut = next;
  }
  return std::string(text.substr(0, cut)) + u8"\u2026 (" + std::to_string(text.size()) +
         " bytes in all)";
}

}  // namespace dampbound::ui
