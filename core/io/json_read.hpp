#pragma once
// A small JSON reader (RFC 8259) for the files dampbound writes and reads back: the limits
// baseline of `diff --save` (core/analysis/limits_diff.hpp). Numbers are read in the "C"
// locale; non-finite numbers, which JSON cannot hold, are written by dampbound as the strings
// "inf", "-inf" and "nan" (json_limit below reads them).
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace dampbound {

struct JsonValue {
  enum class Kind { null, boolean, number, string, array, object };
  Kind kind = Kind::null;
  bool boolean = false;
  double number = 0;
  std::string string;
  std::vector<JsonValue> array;
  std::vector<std::pair<std::string, JsonValue>> object;  ///< in file order
  /// The member `key` of an object; nullptr when absent or not an object.
  const JsonValue* find(const std::string& key) const;
};

/// Parses one JSON document. Throws InputError "PATH: line L: ..." for text that is not JSON
/// (nesting deeper than 64 included).
JsonValue parse_json(std::string_view text, const std::string& path);

/// A number, or one of the strings "inf", "-inf", "nan"; InputError naming `path` and `what`
/// otherwise.
double json_limit(const JsonValue& value, const std::string& path, const std::string& what);
/// JSON text for a double at full precision, non-finite values as the strings above.
std::string json_limit_text(double x);

}  // namespace dampbound
