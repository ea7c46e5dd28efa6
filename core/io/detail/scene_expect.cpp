// The [[expect]] tables of a scene file: what `check` asserts, under which verdict rule
// (SPEC 5's first entry or SPEC 8's settled rule).
#include "core/io/detail/scene_expect.hpp"
#include "core/io/detail/scene_reader.hpp"

namespace dampbound::scene_file {

namespace {

/// An inclusive [min, max] range of iterations.
void read_range(const Reader& r, const toml::node& n, const std::string& key,
                std::optional<int>& lo, std::optional<int>& hi) {
  const toml::array* a = n.as_array();
  if (!a || a->size() != 2) r.fail(n, key + " must be [min, max]");
  const long long first = r.integer(*a->get(0), key), last = r.integer(*a->get(1), key);
  // Checked before the narrowing: [4294967296, ...] became [0, ...].
  if (first < 0 || last > 100000000) r.fail(n, key + " must lie in 0..100000000");
  lo = static_cast<int>(first);
  hi = static_cast<int>(last);
  if (*lo > *hi) r.fail(n, key + " range is inverted");
}

/// An inclusive [min, max] range of numbers.
void read_number_range(const Reader& r, const toml::node& n, const std::string& key,
                       std::optional<double>& lo, std::optional<double>& hi) {
  const toml::array* a = n.as_array();
  if (!a || a->size() != 2) r.fail(n, key + " must be [min, max]");
  lo = r.non_negative(*a->get(0), key);
  hi = r.non_negative(*a->get(1), key);
  if (*lo > *hi) r.fail(n, key + " range is inverted");
}

}  // namespace

void read_expectations(const Reader& r, const toml::table& root, SceneSpec& s) {
  for (const toml::table& t : r.tables(root, "expect")) {
    Expectation x;
    x.line = static_cast<int>(t.source().begin.line);
    if (auto* n = t.get("run")) {
      x.run = r.string(*n, "run");
      bool found = false;
      for (const auto& run : s.runs) found = found || run.label == x.run;
      if (!found) r.fail(*n, "expect refers to run '" + x.run + "', which is not declared");
    }
    if (auto* n = t.get("rule")) {
      const auto rule = parse_stop_rule(r.string(*n, "rule"));
      if (!rule) r.fail(*n, "rule must be first-entry or settled");
      x.rule = *rule;
    }
    const bool settled = x.rule == StopRule::settled;
    if (auto* n = t.get("outcome")) {
      const std::string o = r.string(*n, "outcome");
      // SPEC 8: each rule has its own verdicts; diverged belongs to both.
      for (Outcome c : final_outcomes(x.rule))
        if (o == to_string(c)) x.outcome = c;
      if (!x.outcome)
        r.fail(*n, settled ? "outcome must be settled, diverged or not_settled under rule "
                             "settled (give rule = \"first-entry\" for restored, not_restored)"
                           : "outcome must be restored, diverged or not_restored under rule "
                             "first-entry (give rule = \"settled\" for settled, not_settled)");
    }
    if (auto* n = t.get("iterations")) read_range(r, *n, "iterations", x.iterations_min, x.iterations_max);
    if (auto* n = t.get("first_entry"))
      read_range(r, *n, "first_entry", x.first_entry_min, x.first_entry_max);
    // The first-entry rule stops at the entry: an exit or a settled iteration is never seen.
    const auto settled_only = [&](const toml::node& n, const char* key) {
      if (!settled) r.fail(n, std::string(key) + " needs rule = \"settled\" (the first-entry rule "
                              "stops at the entry)");
    };
    if (auto* n = t.get("left")) {
      settled_only(*n, "left");
      x.left = r.boolean(*n, "left");
    }
    if (auto* n = t.get("left_at")) {
      settled_only(*n, "left_at");
      read_range(r, *n, "left_at", x.left_at_min, x.left_at_max);
    }
    if (auto* n = t.get("settled_at")) {
      settled_only(*n, "settled_at");
      read_range(r, *n, "settled_at", x.settled_at_min, x.settled_at_max);
    }
    if (auto* n = t.get("max_displacement_below"))
      x.max_displacement_below = r.positive(*n, "max_displacement_below");
    // Node-step counts: a double beyond 1e18 would not convert to long long (1e300 wrapped).
    auto count = [&](const toml::node& c, const char* what) {
      const double v = r.non_negative(c, what);
      if (v > 1e18) r.fail(c, std::string(what) + " must be at most 1e18");
      return static_cast<long long>(v);
    };
    if (auto* n = t.get("unstabilisable_max"))
      x.unstabilisable_max = count(*n, "unstabilisable_max");
    if (auto* n = t.get("violations_max")) x.violations_max = count(*n, "violations_max");
    if (auto* n = t.get("violations_min")) x.violations_min = count(*n, "violations_min");
    if (auto* n = t.get("mass_scale_dt")) {
      if (!settled) r.fail(*n, "mass_scale_dt needs rule = \"settled\" (SPEC 11 checks the "
                               "scaled masses by a run under the settled rule)");
      x.mass_scale_dt = r.positive(*n, "mass_scale_dt");
    }
    const auto with_dt = [&](const toml::node& n, const char* key) {
      if (!x.mass_scale_dt) r.fail(n, std::string(key) + " needs mass_scale_dt (the target step)");
    };
    if (auto* n = t.get("added_mass_percent")) {
      with_dt(*n, "added_mass_percent");
      read_number_range(r, *n, "added_mass_percent", x.added_mass_min, x.added_mass_max);
    }
    if (auto* n = t.get("scaled_nodes")) {
      with_dt(*n, "scaled_nodes");
      read_range(r, *n, "scaled_nodes", x.scaled_nodes_min, x.scaled_nodes_max);
    }
    if (auto* n = t.get("dt_limit_min")) x.dt_limit_min = r.positive(*n, "dt_limit_min");
    if (auto* n = t.get("substeps_max")) {
      const long long v = r.integer(*n, "substeps_max");
      if (v < 1 || v > 100000000) r.fail(*n, "substeps_max must lie in 1..100000000");
      x.substeps_max = static_cast<int>(v);
    }
    if (auto* n = t.get("frame_dt")) {
      if (!x.substeps_max) r.fail(*n, "frame_dt goes with substeps_max");
      x.frame_dt = r.positive(*n, "frame_dt");
    }
    if (!x.outcome && !x.iterations_min && !x.first_entry_min && !x.left && !x.left_at_min &&
        !x.settled_at_min && !x.max_displacement_below && !x.unstabilisable_max &&
        !x.violations_max && !x.violations_min && !x.added_mass_min && !x.scaled_nodes_min &&
        !x.dt_limit_min && !x.substeps_max)
      r.fail(t,
             "[[expect]] asserts nothing: give outcome, iterations, first_entry, left, left_at, "
             "settled_at, max_displacement_below, unstabilisable_max, violations_max, "
             "violations_min, added_mass_percent, scaled_nodes, dt_limit_min or substeps_max");
    s.expectations.push_back(x);
  }
}

}  // namespace dampbound::scene_file
