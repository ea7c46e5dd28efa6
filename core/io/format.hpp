#pragma once
// Numbers and text as dampbound prints them: exact round-trip decimals for files, a fixed
// number of significant digits for people, JSON literals, and text made safe for one line.
//
// Every number dampbound writes or reads as text goes through the "C" locale, whatever the
// program's: a host that called setlocale(LC_ALL, "") in a German or French locale (a Qt
// program, a Python script calling locale.setlocale) would otherwise get "0,5" in its CSV and
// JSON, and the mesh readers would take "0.57" for a bad number (docs/embedding.md).
#include <cstddef>
#include <string>
#include <string_view>

namespace dampbound {

/// TEXT with control characters (newline, escape, ...) shown as \xNN: safe on one terminal line.
std::string printable(std::string_view text);

/// Shortest decimal (15 to 17 digits) that reads back as the same double; non-finite values print as "inf" ("-inf").
std::string format_number(double x);

/// `significant` digits (%g) for people to read; NaN prints as `not_a_number`, infinities as
/// "inf" / "-inf". Every table, status line and message of dampbound uses this one.
std::string format_digits(double x, int significant, std::string_view not_a_number = "n/a");

/// The significant digits of what people read (6 unless the CLI's --digits says otherwise);
/// files keep format_number's round-trip precision.
int human_digits();
void set_human_digits(int digits);
/// format_digits(x, human_digits()).
std::string format_human(double x, std::string_view not_a_number = "n/a");
/// "lo..hi" in format_human's digits, or one number where both ends read alike.
std::string format_human_range(double lo, double hi);

/// "1 spring", "3 springs", "2 classes": a count and its noun, plural unless the count is 1.
std::string plural(long long n, std::string_view noun);

/// JSON number, or null when not finite (JSON has no inf or NaN).
std::string json_number(double x);

/// TEXT with &, <, > and " as XML entities (JUnit files).
std::string xml_escape(const std::string& s);

/// JSON string literal with escapes.
std::string json_string(const std::string& s);

/// std::snprintf in the "C" locale (a '.' for the decimal point), for the calling thread only.
int c_snprintf(char* buffer, std::size_t size, const char* format, ...)
    __attribute__((format(printf, 3, 4)));

/// std::strtod in the "C" locale: the same grammar (leading space, sign, hex, inf, nan).
double c_strtod(const char* text, char** end);

/// While it lives, the calling thread formats and reads numbers in the "C" locale (for
/// std::fprintf and the like); other threads keep theirs.
class CNumericScope {
 public:
  CNumericScope();
  ~CNumericScope();
  CNumericScope(const CNumericScope&) = delete;
  CNumericScope& operator=(const CNumericScope&) = delete;

 private:
  void* previous_;
};

}  // namespace dampbound
