#include "core/io/format.hpp"

#include <atomic>

#include <clocale>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <locale.h>
#include <sstream>
#include <stdexcept>
#include <stdlib.h>

namespace dampbound {
namespace {

/// The "C" locale, made once (POSIX newlocale; a per-thread uselocale switches to it).
locale_t c_locale() {
  static const locale_t c = [] {
    const locale_t l = newlocale(LC_ALL_MASK, "C", static_cast<locale_t>(nullptr));
    if (l == static_cast<locale_t>(nullptr)) throw std::runtime_error("cannot make the C locale");
    return l;
  }();
  return c;
}

}  // namespace

CNumericScope::CNumericScope() : previous_(uselocale(c_locale())) {}
CNumericScope::~CNumericScope() { uselocale(static_cast<locale_t>(previous_)); }

int c_snprintf(char* buffer, std::size_t size, const char* format, ...) {
  const CNumericScope c;
  va_list args;
  va_start(args, format);
  const int n = std::vsnprintf(buffer, size, format, args);
  va_end(args);
  return n;
}

double c_strtod(const char* text, char** end) { return strtod_l(text, end, c_locale()); }

std::string printable(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", u);
      out += buf;
    } else {
      out += c;
    }
  }
  return out;
}

std::string format_number(double x) {
  if (std::isnan(x) || (std::isinf(x) && x > 0)) return "inf";
  if (std::isinf(x)) return "-inf";
  // The shortest of %.15g..%.17g that reads back as the same double.
  char buf[32];
  for (int digits = 15; digits <= 17; ++digits) {
    c_snprintf(buf, sizeof buf, "%.*g", digits, x);
    if (c_strtod(buf, nullptr) == x) break;
  }
  return buf;
}

std::string format_digits(double x, int significant, std::string_view not_a_number) {
  if (std::isnan(x)) return std::string(not_a_number);
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buf[40];
  c_snprintf(buf, sizeof buf, "%.*g", significant, x);
  return buf;
}

namespace {
std::atomic<int> g_human_digits{6};
}  // namespace

int human_digits() { return g_human_digits.load(std::memory_order_relaxed); }
void set_human_digits(int digits) { g_human_digits.store(digits, std::memory_order_relaxed); }
std::string format_human(double x, std::string_view not_a_number) {
  return format_digits(x, human_digits(), not_a_number);
}

std::string format_human_range(double lo, double hi) {
  const std::string a = format_human(lo), b = format_human(hi);
  return a == b ? a : a + ".." + b;
}

std::string plural(long long n, std::string_view noun) {
  std::string out = std::to_string(n) + " " + std::string(noun);
  if (n == 1 || noun.empty()) return out;
  const char last = noun.back();
  const bool sibilant = last == 's' || last == 'x' ||
                        (noun.size() > 1 && noun.substr(noun.size() - 2) == "sh") ||
                        (noun.size() > 1 && noun.substr(noun.size() - 2) == "ch");
  return out + (sibilant ? "es" : "s");
}

std::string json_number(double x) { return std::isfinite(x) ? format_number(x) : "null"; }

std::string xml_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      default: o += c;
    }
  }
  return o;
}

std::string json_string(const std::string& s) {
  std::ostringstream os;
  os << '"';
  for (char c : s) {
    switch (c) {
      case '"': os << "\\\""; break;
      case '\\': os << "\\\\"; break;
      case '\n': os << "\\n"; break;
      case '\t': os << "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          os << buf;
        } else {
          os << c;
        }
    }
  }
  os << '"';
  return os.str();
}

}  // namespace dampbound
