#include "core/io/scene_text.hpp"

#include <algorithm>
#include <atomic>

#include "dampbound/physics/error.hpp"

namespace dampbound {

namespace {

std::atomic<bool> g_unrestricted{false};

[[noreturn]] void fail(const std::string& path, int line, const std::string& msg) {
  throw InputError(path + ":" + std::to_string(line) + ": " + msg);
}

/// Length of the UTF-8 sequence at s[i], or 0 when it is malformed (RFC 3629: no overlong
/// forms, no surrogates, nothing above U+10FFFF).
size_t utf8_length(const std::string& s, size_t i) {
  const auto b = [&](size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned c = b(i);
  size_t n = 0;
  unsigned lo = 0x80, hi = 0xBF;
  if (c < 0x80) return 1;
  if (c >= 0xC2 && c <= 0xDF) n = 2;
  else if (c >= 0xE0 && c <= 0xEF) n = 3, lo = c == 0xE0 ? 0xA0 : 0x80, hi = c == 0xED ? 0x9F : 0xBF;
  else if (c >= 0xF0 && c <= 0xF4) n = 4, lo = c == 0xF0 ? 0x90 : 0x80, hi = c == 0xF4 ? 0x8F : 0xBF;
  else return 0;
  if (i + n > s.size()) return 0;
  if (b(i + 1) < lo || b(i + 1) > hi) return 0;
  for (size_t k = 2; k < n; ++k)
    if (b(i + k) < 0x80 || b(i + k) > 0xBF) return 0;
  return n;
}

}  // namespace

void check_scene_text(const std::string& text, const std::string& path) {
  // toml++ 3.3 takes EF BB for the start of a byte-order mark and reaches an internal
  // "unreachable" marker when the third byte is not BF (EF BB BB is U+FEFB, valid UTF-8).
  if (text.compare(0, 2, "\xEF\xBB") == 0 && text.compare(0, 3, "\xEF\xBB\xBF") != 0)
    fail(path, 1, "the file starts with a broken byte-order mark (EF BB without BF)");
  int line = 1;
  for (size_t i = 0; i < text.size();) {
    if (text[i] == '\0') fail(path, line, "the file holds a NUL byte (not a text file)");
    const size_t n = utf8_length(text, i);
    if (n == 0) fail(path, line, "the file is not valid UTF-8");
    if (text[i] == '\n') ++line;
    i += n;
  }
  // Nesting outside strings and comments: '[' and '{' open a level (table headers, arrays,
  // inline tables), and each '.' of a key adds a part. Values' dots (1.5) come after '='.
  line = 1;
  std::string open;  // the '[' and '{' not yet closed, innermost last
  int key_parts = 1;
  bool in_value = false;  // after '=' on this logical line
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      if (open.empty()) in_value = false, key_parts = 1;
      continue;
    }
    if (c == '#') {
      while (i + 1 < text.size() && text[i + 1] != '\n') ++i;
      continue;
    }
    if (c == '"' || c == '\'') {
      const bool multi = text.compare(i, 3, std::string(3, c)) == 0;
      const std::string close = multi ? std::string(3, c) : std::string(1, c);
      for (i += close.size(); i < text.size(); ++i) {
        if (c == '"' && text[i] == '\\') {
          ++i;
          if (i < text.size() && text[i] == '\n') ++line;
          continue;
        }
        if (text[i] == '\n') {
          if (!multi) break;  // an unterminated string: the parser names it
          ++line;
        }
        if (text.compare(i, close.size(), close) == 0) {
          i += close.size() - 1;
          break;
        }
      }
      continue;
    }
    if (c == '[' || c == '{') {
      open += c;
      if (open.size() > static_cast<size_t>(kMaxTomlNesting))
        fail(path, line, "arrays, tables or inline tables nested deeper than " +
                             std::to_string(kMaxTomlNesting) + " levels");
      if (c == '{') in_value = false, key_parts = 1;  // keys again inside an inline table
    } else if (c == ']' || c == '}') {
      if (!open.empty()) open.pop_back();
      if (c == '}') in_value = true;
    } else if (c == '=') {
      in_value = true;
      key_parts = 1;
    } else if (c == ',' && !open.empty() && open.back() == '{') {
      // inside an inline table a comma starts the next key
      in_value = false;
      key_parts = 1;
    } else if (c == '.' && !in_value) {
      if (++key_parts > kMaxTomlNesting)
        fail(path, line, "a dotted key or table name has more than " +
                             std::to_string(kMaxTomlNesting) + " parts");
    }
  }
}

void set_scene_paths_unrestricted(bool allow) { g_unrestricted = allow; }
bool scene_paths_unrestricted() { return g_unrestricted; }

std::string scene_relative_path(const std::string& scene_path, const std::string& file) {
  if (!g_unrestricted) {
    if (file.front() == '/') {
      throw InputError(
          "is an absolute path; a scene names files in its own folder (--allow-any-path "
          "lifts this)");
    }
    for (size_t start = 0; start <= file.size();) {
      const size_t slash = std::min(file.find('/', start), file.size());
      if (file.compare(start, slash - start, "..") == 0 && slash - start == 2) {
        throw InputError("climbs out of the scene's folder with '..' (--allow-any-path lifts this)");
      }
      start = slash + 1;
    }
  }
  if (file.front() == '/') return file;
  const auto slash = scene_path.find_last_of('/');
  return slash == std::string::npos ? file : scene_path.substr(0, slash + 1) + file;
}

void check_plain_text(const std::string& text, const std::string& what, const std::string& path,
                      int line) {
  for (char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f)
      fail(path, line, what + " holds a control character (a newline, tab or escape)");
  }
}

}  // namespace dampbound
