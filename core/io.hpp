#pragma once
// Output that is written whole or not at all, and number formatting that never prints NaN.
#include <functional>
#include <iosfwd>
#include <string>

namespace dampbound {

/// Writes through `write` into PATH.tmp.<pid>, then renames onto PATH, so a reader never sees
/// a half-written file. Throws InputError naming the path when it cannot be written.
void write_file_atomic(const std::string& path, const std::function<void(std::ostream&)>& write);

/// The whole file as bytes; InputError naming the path when it cannot be read.
std::string read_file_text(const std::string& path);

/// Fails early (InputError naming the path) when PATH's directory cannot take a new file.
void check_writable(const std::string& path);

/// Shortest decimal (15 to 17 digits) that reads back as the same double; non-finite values print as "inf" ("-inf").
std::string format_number(double x);

/// JSON number, or null when not finite (JSON has no inf or NaN).
std::string json_number(double x);

/// JSON string literal with escapes.
std::string json_string(const std::string& s);

}  // namespace dampbound
