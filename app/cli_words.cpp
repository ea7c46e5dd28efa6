#include "app/cli_words.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "core/io/format.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound::app {

namespace {

/// Optimal string alignment distance: Levenshtein plus the swap of two neighbours.
size_t edit_distance(const std::string& a, const std::string& b) {
  const size_t n = a.size(), m = b.size();
  std::vector<std::vector<size_t>> d(n + 1, std::vector<size_t>(m + 1));
  for (size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (size_t i = 1; i <= n; ++i)
    for (size_t j = 1; j <= m; ++j) {
      const size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[n][m];
}

/// Every spelling of the options of `app` ("--gamma", "-o").
void option_names(const CLI::App& app, std::vector<std::string>& out) {
  for (const CLI::Option* o : app.get_options()) {
    for (const std::string& l : o->get_lnames()) out.push_back("--" + l);
    for (const std::string& s : o->get_snames()) out.push_back("-" + s);
  }
}

}  // namespace

std::optional<std::string> nearest_name(const std::string& word,
                                        const std::vector<std::string>& names) {
  std::optional<std::string> best;
  size_t best_d = 3;  // at most 2 edits
  for (const std::string& n : names) {
    const size_t d = edit_distance(word, n);
    if (d < best_d && 2 * d < word.size()) {
      best_d = d;
      best = n;
    }
  }
  return best;
}

std::optional<std::string> unknown_flag_message(const CLI::App& root,
                                                const std::vector<std::string>& args) {
  const CLI::App* sub = nullptr;
  std::vector<std::string> names;
  option_names(root, names);
  for (const std::string& arg : args) {
    if (arg.empty()) continue;
    if (arg[0] != '-') {
      if (sub == nullptr)
        for (const CLI::App* s : root.get_subcommands(std::function<bool(const CLI::App*)>{}))
          if (s->get_name() == arg) {
            sub = s;
            option_names(*s, names);
            break;
          }
      continue;
    }
    if (arg == "--") break;
    const std::string word = arg.substr(0, arg.find('='));
    if (std::find(names.begin(), names.end(), word) != names.end()) continue;
    // A negative number (or a vector such as -1,0,0) is a value, not a flag.
    if (word.size() > 1 && (std::isdigit(static_cast<unsigned char>(word[1])) || word[1] == '.'))
      continue;
    const std::string where = sub ? " for '" + sub->get_name() + "'" : "";
    const std::string help = sub ? "dampbound " + sub->get_name() + " --help" : "dampbound --help";
    if (const auto near = nearest_name(word, names))
      return "unknown flag " + printable(word) + where + " (did you mean " + *near + "?)";
    return "unknown flag " + printable(word) + where + " (" + help + " lists the flags)";
  }
  return std::nullopt;
}

void refuse_empty_values(const CLI::App& cmd) {
  std::vector<const CLI::App*> apps = {&cmd};
  if (cmd.get_parent() != nullptr) apps.push_back(cmd.get_parent());
  for (const CLI::App* app : apps)
    for (const CLI::Option* o : app->get_options()) {
      if (o->count() == 0 || o->get_expected_min() == 0) continue;  // a flag has no value
      for (const std::string& r : o->results())
        if (r.empty())
          throw InputError(o->get_name() + ": the value is empty (give " +
                           (o->get_positional() ? "one" : "a value or leave the flag out") + ")");
    }
}

CLI::Validator whole_range(long long lo, long long hi) {
  const std::string range = "from " + std::to_string(lo) + " to " + std::to_string(hi);
  return CLI::Validator(
      [lo, hi, range](std::string& s) -> std::string {
        errno = 0;
        char* end = nullptr;
        const long long v = std::strtoll(s.c_str(), &end, 10);
        if (s.empty() || *end != '\0' || end == s.c_str())
          return "'" + printable(s) + "' is not a whole number (give one " + range + ")";
        if (errno == ERANGE || v < lo || v > hi)
          return "'" + printable(s) + "' is outside the accepted values " + range;
        return {};
      },
      std::to_string(lo) + ".." + std::to_string(hi));
}

CLI::Validator number_range(double lo, double hi) {
  const std::string range = "from " + format_human(lo) + " to " + format_human(hi);
  return CLI::Validator(
      [lo, hi, range](std::string& s) -> std::string {
        char* end = nullptr;
        const double v = c_strtod(s.c_str(), &end);
        if (s.empty() || *end != '\0' || end == s.c_str() || !std::isfinite(v))
          return "'" + printable(s) + "' is not a number (give one " + range + ")";
        if (v < lo || v > hi) return "'" + printable(s) + "' is outside the accepted values " + range;
        return {};
      },
      format_human(lo) + ".." + format_human(hi));
}

}  // namespace dampbound::app
