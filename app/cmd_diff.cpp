// dampbound diff OLD NEW: two scenes' limits side by side (or a scene against a saved baseline),
// what changed them, and exit 1 when the exact dt limit fell by more than --max-drop percent
// (core/analysis/limits_diff.hpp; docs/guide.md, "diff").
#include <cmath>
#include <cstdio>
#include <memory>
#include <ostream>

#include "app/commands.hpp"
#include "app/options.hpp"
#include "core/analysis/limits_diff.hpp"
#include "core/io/files.hpp"
#include "core/io/format.hpp"
#include "core/physics/damping_ratio.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound::app::cmd_diff {
namespace {

struct DiffArgs {
  std::string old_arg, new_arg, save, junit;
  double frame_dt = 0, max_drop = 20, factor_budget = 0;
  CLI::Option* frame_dt_opt = nullptr;
};

bool is_baseline(const std::string& arg) {
  return arg.size() > 5 && arg.compare(arg.size() - 5, 5, ".json") == 0;
}

LimitsSnapshot snapshot_of(const std::string& arg, const DiffArgs& a) {
  if (is_baseline(arg)) return read_limits_json(read_file_text(arg), arg);
  SceneSpec scene = load_scene_arg(arg);
  Params p = scene.params;
  resolve_zeta(scene.model, p);
  p.policy = DampingPolicy::fixed;
  ExactOptions options;
  options.threads = 0;
  options.max_factor_flops = a.factor_budget * 1e9;
  LimitsSnapshot s = limits_snapshot(scene, p, options);
  if (s.scene.empty()) s.scene = arg;
  return s;
}

std::string seconds(double x) {
  return std::isnan(x) ? "not computed" : format_human(x) + " s";
}

std::string change(double a, double b) {
  if (!(a > 0) || std::isinf(a) || std::isnan(b)) return "";
  return (b >= a ? "+" : "") + format_digits(100 * (b / a - 1), 3) + "%";
}

void row(const char* what, const std::string& a, const std::string& b, const std::string& c = "") {
  std::printf("  %-22s %-26s %-26s %s\n", what, a.c_str(), b.c_str(), c.c_str());
}

void print_worst(const char* which, const LimitsSnapshot& s) {
  std::printf("worst nodes of %s by dt_safe_i (SPEC 9/10):\n", which);
  for (const LimitsSnapshot::Node& n : s.worst) {
    const Vec3& x = s.rest[static_cast<size_t>(n.node)];
    std::printf("  %7d  %-12s at (%s, %s, %s)  %s\n", n.node, seconds(n.dt_safe).c_str(),
                format_digits(x.x(), 4).c_str(), format_digits(x.y(), 4).c_str(),
                format_digits(x.z(), 4).c_str(), n.cause.c_str());
  }
}

void write_junit(const std::string& path, const LimitsSnapshot& o, const LimitsSnapshot& n,
                 const std::string& name, bool failed, const std::string& message) {
  write_file_atomic(path, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"dampbound diff\" "
           "tests=\"1\" failures=\""
        << (failed ? 1 : 0) << "\">\n  <testsuite name=\"" << xml_escape(o.scene + " -> " + n.scene)
        << "\" tests=\"1\" failures=\"" << (failed ? 1 : 0) << "\">\n    <testcase classname=\""
        << xml_escape(o.scene + " -> " + n.scene) << "\" name=\"" << xml_escape(name) << "\">";
    if (failed) out << "\n      <failure message=\"" << xml_escape(message) << "\"/>\n    ";
    out << "</testcase>\n  </testsuite>\n</testsuites>\n";
  });
}

int run(const DiffArgs& a) {
  if (!a.save.empty()) check_writable(a.save);
  if (!a.junit.empty()) check_writable(a.junit);
  if (a.new_arg.empty() && a.save.empty())
    throw InputError("diff: give NEW, or --save FILE to write OLD's limits as a baseline");
  const LimitsSnapshot o = snapshot_of(a.old_arg, a);
  if (a.new_arg.empty()) {
    write_file_atomic(a.save, [&](std::ostream& out) { write_limits_json(out, o); });
    std::printf("baseline %s: exact dt limit %s, safe step %s; wrote %s\n", o.scene.c_str(),
                seconds(o.dt_limit).c_str(), seconds(o.dt_safe).c_str(), a.save.c_str());
    return 0;
  }
  const LimitsSnapshot n = snapshot_of(a.new_arg, a);
  if (!a.save.empty())
    write_file_atomic(a.save, [&](std::ostream& out) { write_limits_json(out, n); });
  const LimitsDiff d = diff_limits(o, n);
  std::printf("limits at rest (exact analysis and SPEC 9/10's safe bound), each scene at its own "
              "parameters\n");
  row("", "OLD " + o.scene, "NEW " + n.scene, "change");
  row("nodes", std::to_string(o.rest.size()), std::to_string(n.rest.size()),
      std::to_string(d.matched_nodes) + " matched by position" + (d.renumbered ? " (renumbered)" : ""));
  row("springs", std::to_string(o.spring_i.size()), std::to_string(n.spring_i.size()));
  row("dt", seconds(o.params.dt), seconds(n.params.dt));
  row("exact dt limit", seconds(o.dt_limit), seconds(n.dt_limit), change(o.dt_limit, n.dt_limit));
  row("gamma range at dt", "[" + format_human(o.gamma_lo) + ", " + format_human(o.gamma_hi) + ")",
      "[" + format_human(n.gamma_lo) + ", " + format_human(n.gamma_hi) + ")");
  row("safe step", seconds(o.dt_safe) + " (node " + std::to_string(o.dt_safe_node) + ")",
      seconds(n.dt_safe) + " (node " + std::to_string(n.dt_safe_node) + ")",
      change(o.dt_safe, n.dt_safe));
  if (a.frame_dt_opt->count()) {
    const int so = limit_substeps(a.frame_dt, o.dt_limit), sn = limit_substeps(a.frame_dt, n.dt_limit);
    const auto text = [](int k) { return k > 0 ? std::to_string(k) : std::string("none"); };
    row(("substeps of " + format_human(a.frame_dt) + " s").c_str(), text(so), text(sn));
  }
  print_worst("OLD", o);
  print_worst("NEW", n);
  if (!d.parameters.empty()) {
    std::printf("parameters changed:");
    for (const std::string& p : d.parameters) std::printf(" %s;", p.c_str());
    std::printf("\n");
  }
  if (!n.mode_nodes.empty()) {
    std::printf("NEW's limiting mode (the index's top eigenvector at its dt limit) sits at");
    for (size_t k = 0; k < n.mode_nodes.size(); ++k)
      std::printf(" %d (%s%%)", n.mode_nodes[k], format_digits(100 * n.mode_share[k], 3).c_str());
    std::printf("\n");
  }
  if (!d.changes.empty()) {
    std::printf("what changed at the nodes that limit NEW (its mode, worst nodes and largest "
                "falls; NEW's node numbers):\n");
    for (const LimitChange& c : d.changes)
      std::printf("  %s%s\n", c.what.c_str(),
                  c.weight > 0 ? (" [" + format_digits(100 * c.weight, 3) + "% of the mode]").c_str() : "");
  } else {
    std::printf("no node or spring changed at the nodes that limit NEW\n");
  }
  std::printf("changed over the whole scene: %d nodes (mass, anchor or fixed), %d new nodes, %d "
              "removed, %d springs (new, removed, stiffness or rest length)\n",
              d.changed_nodes, d.new_nodes, d.removed_nodes, d.changed_springs);
  for (const LimitsDiff::Fall& f : d.falls)
    std::printf("  node %d: dt_safe_i %s -> %s\n", f.node, seconds(f.old_dt).c_str(),
                seconds(f.new_dt).c_str());
  const std::string name = "exact dt limit falls by at most " + format_human(a.max_drop) + "%";
  std::string message;
  bool failed = false;
  if (std::isnan(n.dt_limit) || std::isnan(o.dt_limit)) {
    failed = true;
    message = "the exact dt limit was not computed (" + (std::isnan(n.dt_limit) ? n.method : o.method) +
              "; --factor-budget)";
  } else if (d.drop * 100 > a.max_drop) {
    failed = true;
    message = "the exact dt limit fell by " + format_digits(100 * d.drop, 3) + "% (" +
              seconds(o.dt_limit) + " -> " + seconds(n.dt_limit) + "), more than " +
              format_human(a.max_drop) + "%" +
              (d.changes.empty() ? std::string() : "; first change: " + d.changes[0].what);
  }
  std::printf("%s: %s\n", failed ? "FAIL" : "ok",
              failed ? message.c_str()
                     : ("the exact dt limit moved " + change(o.dt_limit, n.dt_limit) +
                        " (allowed drop " + format_human(a.max_drop) + "%)").c_str());
  if (!a.junit.empty()) write_junit(a.junit, o, n, name, failed, message);
  return failed ? 1 : 0;
}

std::function<int()> setup(CLI::App& root) {
  auto a = std::make_shared<DiffArgs>();
  CLI::App* cmd = root.add_subcommand(
      "diff",
      "Compare two scenes' limits (or a scene with a baseline written by diff --save): exact dt "
      "limit, gamma range, safe step, substeps, worst nodes, and the nodes and springs that "
      "changed the limit (matched by position). Exit 1 when the dt limit falls by more than "
      "--max-drop percent.");
  cmd->add_option("old", a->old_arg, "scene file, shipped scene name, or baseline .json")->required();
  cmd->add_option("new", a->new_arg, "scene file, shipped scene name, or baseline .json");
  cmd->add_option("--save", a->save, "write NEW's limits (OLD's when NEW is not given) as a "
                                     "baseline .json");
  a->frame_dt_opt = cmd->add_option("--frame-dt", a->frame_dt,
                                    "frame time (s): the fewest substeps below each dt limit")
                        ->check(finite_positive());
  cmd->add_option("--max-drop", a->max_drop, "largest allowed fall of the exact dt limit, in "
                                             "percent (default 20)")
      ->check(CLI::Range(0.0, 100.0));
  cmd->add_option("--junit", a->junit, "also write the verdict as JUnit XML to this file");
  add_factor_budget_option(cmd, a->factor_budget);
  return [a] { return run(*a); };
}

const bool registered = register_command("diff", setup);

}  // namespace
}  // namespace dampbound::app::cmd_diff
