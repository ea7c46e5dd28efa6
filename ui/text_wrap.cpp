#include "ui/text_wrap.hpp"

namespace dampbound::ui {

namespace {
bool blank(char c) { return c == ' ' || c == '\t'; }

/// Appends `word` to `out`, whose current line starts at `line` and is empty: a word wider
/// than `width` is split over lines, after its last '-' or '/' that fits, else after as many
/// characters as fit (at least one). Returns where the last line starts.
size_t append_long_word(std::string& out, size_t line, std::string_view word, float width,
                        const std::function<float(std::string_view)>& measure) {
  while (measure(word) > width && word.size() > 1) {
    size_t fit = 1;  // the longest prefix that fits, at least one character
    while (fit < word.size() && measure(word.substr(0, fit + 1)) <= width) ++fit;
    size_t cut = fit;
    for (size_t k = fit; k > 1; --k)
      if (word[k - 1] == '-' || word[k - 1] == '/') {
        cut = k;
        break;
      }
    out.append(word.substr(0, cut));
    out += '\n';
    line = out.size();
    word.remove_prefix(cut);
  }
  out.append(word);
  return line;
}
}  // namespace

std::string wrap_at_blanks(std::string_view text, float width,
                           const std::function<float(std::string_view)>& measure) {
  std::string out;
  out.reserve(text.size());
  size_t line = 0;  // where the current line starts in `out`
  size_t k = 0;
  while (k < text.size()) {
    if (text[k] == '\n') {
      out += '\n';
      line = out.size();
      ++k;
      continue;
    }
    // The blanks before the next word, and the word.
    size_t w = k;
    while (w < text.size() && blank(text[w])) ++w;
    size_t end = w;
    while (end < text.size() && !blank(text[end]) && text[end] != '\n') ++end;
    const std::string_view blanks = text.substr(k, w - k), word = text.substr(w, end - w);
    const bool line_empty = out.size() == line;
    if (!line_empty && !word.empty()) {
      const std::string_view candidate(out.data() + line, out.size() - line);
      std::string joined(candidate);
      joined.append(blanks).append(word);
      if (measure(joined) > width) {  // the word goes to a new line, its blanks are dropped
        out += '\n';
        line = append_long_word(out, out.size(), word, width, measure);
        k = end;
        continue;
      }
    }
    out.append(blanks);
    if (line_empty && measure(std::string(out.data() + line, out.size() - line).append(word)) > width)
      line = append_long_word(out, line, word, width, measure);
    else
      out.append(word);
    k = end;
  }
  return out;
}

}  // namespace dampbound::ui
