#pragma once
// The scene file reader's checked accessors (core/io/scene_file.cpp and the files that read parts
// of a scene): every error names the file and the line. Private to core.
#include <functional>
#include <toml++/toml.h>

#include <cmath>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/io/scene_keys.hpp"
#include "dampbound/physics/error.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound::scene_file {

/// Reads one scene file; every error names the file and the line.
class Reader {
 public:
  explicit Reader(std::string path) : path_(std::move(path)) {}

  [[noreturn]] void fail(int line, const std::string& msg) const {
    std::ostringstream os;
    os << path_ << ":" << line << ": " << msg;
    throw InputError(os.str());
  }
  [[noreturn]] void fail(const toml::node& n, const std::string& msg) const {
    fail(static_cast<int>(n.source().begin.line), msg);
  }

  /// Refuses a key of `t` that the scene key table (core/io/scene_keys.cpp) does not list
  /// for `section` ("" for the top level, "[grid]", "[[node]]", ...).
  void check_keys(const toml::table& t, const std::string& section) const {
    for (auto&& [key, value] : t)
      if (!scene_key_allowed(section, key.str()))
        fail(static_cast<int>(key.source().begin.line),
             "unknown key '" + std::string(key.str()) + "' in " +
                 (section.empty() ? std::string("the scene") : section));
  }

  const toml::table& table(const toml::node& n, const std::string& what) const {
    if (!n.is_table()) fail(n, what + " must be a table");
    return *n.as_table();
  }

  /// The array of tables [[KEY]] of `root` (none when absent), each checked to be a table with
  /// only the keys the scene key table lists for [[KEY]].
  std::vector<std::reference_wrapper<const toml::table>> tables(const toml::table& root,
                                                                const std::string& key) const {
    std::vector<std::reference_wrapper<const toml::table>> out;
    const toml::node* n = root.get(key);
    if (!n) return out;
    const toml::array* list = n->as_array();
    const std::string what = "[[" + key + "]]";
    if (!list) fail(*n, key + " must be an array of tables " + what);
    for (auto&& e : *list) {
      const toml::table& t = table(e, what);
      check_keys(t, what);
      out.emplace_back(t);
    }
    return out;
  }

  double number(const toml::node& n, const std::string& what) const {
    if (!n.is_number()) fail(n, what + " must be a number");
    const double x = n.value<double>().value_or(NAN);
    if (!std::isfinite(x)) fail(n, what + " must be finite (got " + std::to_string(x) + ")");
    return x;
  }
  double positive(const toml::node& n, const std::string& what) const {
    const double x = number(n, what);
    if (!(x > 0)) fail(n, what + " must be > 0");
    return x;
  }
  double non_negative(const toml::node& n, const std::string& what) const {
    const double x = number(n, what);
    if (x < 0) fail(n, what + " must be >= 0");
    return x;
  }
  long long integer(const toml::node& n, const std::string& what) const {
    if (!n.is_integer()) fail(n, what + " must be an integer");
    return *n.value<long long>();
  }
  bool boolean(const toml::node& n, const std::string& what) const {
    if (!n.is_boolean()) fail(n, what + " must be true or false");
    return *n.value<bool>();
  }
  std::string string(const toml::node& n, const std::string& what) const {
    if (!n.is_string()) fail(n, what + " must be a string");
    return *n.value<std::string>();
  }
  std::vector<double> numbers(const toml::node& n, size_t count, const std::string& what) const {
    const toml::array* a = n.as_array();
    if (!a || a->size() != count)
      fail(n, what + " must be an array of " + std::to_string(count) + " numbers");
    std::vector<double> out;
    for (auto&& e : *a) out.push_back(number(e, what));
    return out;
  }
  Vec3 vec3(const toml::node& n, const std::string& what) const {
    const auto v = numbers(n, 3, what);
    return {v[0], v[1], v[2]};
  }
  const toml::node& required(const toml::table& t, std::string_view key,
                             const std::string& where) const {
    const toml::node* n = t.get(key);
    if (!n) fail(t, "missing '" + std::string(key) + "' in " + where);
    return *n;
  }

  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace dampbound::scene_file
