#pragma once
// Numbers and text as dampbound prints them: exact round-trip decimals for files, a fixed
// number of significant digits for people, JSON literals, and text made safe for one line.
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

/// JSON number, or null when not finite (JSON has no inf or NaN).
std::string json_number(double x);

/// JSON string literal with escapes.
std::string json_string(const std::string& s);

}  // namespace dampbound
