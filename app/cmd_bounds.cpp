// dampbound bounds: the paper's bounds (eqs. 5, 6) and the runtime check (sec. 5) for given
// parameters, then every stability criterion side by side (SPEC 7, docs/criteria.md): the
// paper's, Delingette's, Provot's, Kacic-Alesic's and the exact linear analysis of the
// integrator, on the two-node system (or a single node) or on a scene.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

#include "app/answer_lines.hpp"
#include "app/commands.hpp"
#include "app/options.hpp"
#include "app/wait_note.hpp"
#include "core/analysis/answer.hpp"
#include "core/analysis/criteria.hpp"
#include "core/analysis/criteria_safe.hpp"
#include "core/analysis/damping_limits.hpp"
#include "core/analysis/equilibrium.hpp"
#include "core/analysis/limits_diff.hpp"
#include "core/analysis/linear_stability_cholesky.hpp"
#include "core/analysis/worst_nodes.hpp"
#include "core/io/format.hpp"
#include "core/io/report.hpp"
#include "core/physics/detail/numbers.hpp"
#include "core/physics/integrate.hpp"
#include "core/physics/safe_bound.hpp"
#include "dampbound/physics/bounds.hpp"
#include "dampbound/physics/error.hpp"
#include "dampbound/run/session.hpp"

namespace dampbound::app::cmd_bounds {
namespace {

struct BoundsArgs {
  std::string scene, v, force, system = "two-node";
  double factor_budget = 0;
  int after = 0, worst = 0;
  bool json = false, brief = false;
  bool equilibrium = false;
  ParamFlags f;  // --m --kappa --dt --gamma --zeta --integrator --kd --rayleigh-*
};

/// SPEC 10's lines where the model has dashpot or Rayleigh damping: the damping ratios, the
/// exact index lambda_max(dt^2 A + 2 dt C^) with the gamma and dt limits, and whether C^
/// leaves modes undamped. Nothing otherwise (the output stays as it was). What `exact` computed
/// (its spectrum, SPEC 10's limits) is taken from it, not computed again; where it was over
/// the factorisation budget, what needs the spectrum or a factorisation says so instead.
void print_damping_lines(const Model& model, const State& state, const Params& p,
                         const ExactStability& exact, double max_factor_flops) {
  if (!model.spring_damping) return;
  auto g5 = [](double x) { return format_human(x); };
  const DampingRatios r = damping_ratios(
      model, state.x, exact.computed() ? exact.spectrum : StiffnessSpectrum{kNaN, kNaN});
  std::printf("\ndamping               kd=%s rayleigh_mass=%s 1/s rayleigh_stiffness=%s s\n",
              format_human(p.kd).c_str(), format_human(p.rayleigh_mass).c_str(),
              format_human(p.rayleigh_stiffness).c_str());
  std::printf("damping ratios        nodal zeta %s; dashpots (%d) zeta_ij %s; ",
              format_human_range(r.nodal_min, r.nodal_max).c_str(), r.dashpots,
              format_human_range(r.dashpot_min, r.dashpot_max).c_str());
  if (exact.computed())
    std::printf("Rayleigh zeta %s at lambda_min = %s, %s at lambda_max = %s 1/s^2\n",
                g5(r.rayleigh_low).c_str(), g5(r.lambda_min).c_str(), g5(r.rayleigh_high).c_str(),
                g5(r.lambda_max).c_str());
  else
    std::printf("Rayleigh zeta not computed (the spectrum is over the factorisation budget)\n");
  if (!integrator_traits(p.integrator).paper_step) {
    std::printf("exact index           derived for the paper's semi-implicit step; not shown "
                "for %s\n",
                to_string(p.integrator));
    return;
  }
  if (!exact.computed()) {
    std::printf("exact index           not computed: %s (--factor-budget); the rows below say "
                "what is proved without a factorisation\n",
                exact.over_budget_reason().c_str());
    return;
  }
  GeneralLimits g;
  try {
    g = exact.spec10 ? exact.general : general_limits(model, state.x, p, max_factor_flops);
  } catch (const FactorisationOverBudget& over) {
    std::printf("exact index           not computed: %s (--factor-budget)\n", over.what());
    return;
  }
  std::printf("exact index           lambda_max(dt^2 A + 2 dt C^) = %s: %s (stable below 4)\n",
              g5(g.index).c_str(), g.index < 4 ? "stable" : "UNSTABLE");
  std::printf("exact limits          gamma < %s, dt < %s s at gamma = %s (%s)\n",
              g5(g.gamma_max).c_str(), g5(g.dt_max).c_str(), format_human(p.gamma).c_str(),
              g.commuting ? "Rayleigh closed forms: C^ commutes with A"
                          : "C^ not diagonal: bisection on the index");
  if (!(g.damping_min > 0))
    std::printf("undamped modes        lambda_min(C^) = %s: C^ leaves modes undamped; they are "
                "marginal at best\n",
                g5(g.damping_min).c_str());
}

Vec3 parse_vec3(const std::string& text, const char* flag) {
  std::istringstream in(text);
  Vec3 out;
  std::string part;
  for (int k = 0; k < 3; ++k) {
    if (!std::getline(in, part, ',')) break;
    try {
      size_t used = 0;
      out[k] = std::stod(part, &used);
      if (used != part.size() || !std::isfinite(out[k])) throw 0;
    } catch (...) {
      throw InputError(std::string(flag) + ": '" + text + "' is not three finite numbers x,y,z");
    }
    if (k == 2 && !in.eof()) break;
    if (k == 2) return out;
  }
  throw InputError(std::string(flag) + ": '" + text + "' is not three numbers x,y,z");
}

/// The table: one line per criterion, then its formula and source indented below.
void print_criteria(const std::vector<CriterionResult>& criteria) {
  std::printf("\n%-44s %-24s %-7s %s\n", "criterion", "value", "verdict", "test");
  for (const CriterionResult& c : criteria) {
    const std::string value = format_human(c.value) + (c.unit.empty() ? "" : " " + c.unit);
    std::printf("%-44s %-24s %-7s %s\n", c.name.c_str(), value.c_str(), to_string(c.verdict),
                c.test.c_str());
    std::printf("    %s  [%s]\n", c.formula.c_str(), c.source.c_str());
  }
}

/// The paper's own lines for --m --kappa --dt [--v --force --gamma] (the command's first job).
void print_paper_lines(const BoundsArgs& a) {
  const double lo = lower_bound(a.f.m, a.f.kappa);
  std::printf("lower bound (eq. 5)   gamma_lo = 2*sqrt(m*kappa) = %s\n", format_human(lo).c_str());
  if (a.v.empty() != a.force.empty()) throw InputError("--v and --force go together");
  if (a.v.empty()) return;
  const Vec3 v = parse_vec3(a.v, "--v"), f = parse_vec3(a.force, "--force");
  const double hi = upper_bound(v, f, a.f.m, a.f.dt);
  std::printf("upper bound (eq. 6)   gamma_hi = |v*m/dt + F|/|v| = %s%s\n",
              format_human(hi).c_str(), v.norm() == 0 ? " (v = 0: damping has no effect)" : "");
  const bool stabilisable = !(lo > hi);
  std::printf("check (sec. 5)        %s\n",
              stabilisable ? "stabilisable: gamma_lo <= gamma_hi"
                           : "UNSTABILISABLE: gamma_lo > gamma_hi, no damping satisfies both");
  if (a.f.gamma_opt->count()) {
    const bool inside = a.f.gamma >= lo && a.f.gamma <= hi;
    std::printf("gamma = %s          %s\n", format_human(a.f.gamma).c_str(),
                inside ? "within the bounds" : "outside the bounds");
  }
}

/// SPEC 9's safe bound at the state, 5 significant digits, with its worst node and its ratio
/// to the exact limit of the paper's step (SPEC 7) when that is the integrator analysed.
void print_safe_lines(const Model& model, const State& state, const Params& p,
                      const ExactStability& exact) {
  const SafeBoundSummary s = safe_bound_summary(model, state.x, p.dt);
  if (s.free_nodes == 0) return;
  const bool paper_step = integrator_traits(exact.integrator).paper_step;
  auto g5 = [](double x) { return format_human(x); };
  auto ratio = [&](double safe, double ex) {
    // the exact rows below are the nodal analysis (SPEC 7); SPEC 10's own follow
    return paper_step && !model.spring_damping && std::isfinite(ex) && ex != 0
               ? ", exact limit " + g5(ex) + ", ratio " + g5(safe / ex)
               : std::string();
  };
  const char* spec = model.spring_damping ? "damped" : "nodal";
  std::printf("\nsafe bound (%s)%sgamma_safe = %s%s at node %d (R = %s 1/s^2)%s\n",
              spec, model.spring_damping ? "  " : "   ", g5(s.gamma_safe).c_str(),
              s.gamma_scaled ? " (the user's gamma: gamma_i = gamma * gamma_scale_i)" : "",
              s.gamma_node, g5(s.row_sum).c_str(), ratio(s.gamma_safe, exact.gamma_hi).c_str());
  std::printf("safe step (%s)%sdt_safe = %s at gamma = %s, node %d%s\n", spec,
              model.spring_damping ? "   " : "    ", g5(s.dt_safe).c_str(),
              (format_human(p.gamma) + " (zeta " + zeta_text(damping_ratio_range(model)) + ")").c_str(),
              s.dt_node,
              ratio(s.dt_safe, exact.dt_max).c_str());
  if (s.infeasible.empty()) {
    std::printf("critical damping      %s at every free node (gamma_lo_i <= gamma_safe_i)\n",
                paper_step ? "guaranteed" : "within the safe bound");
  } else {
    std::printf("critical damping      NOT guaranteed at %zu of %d nodes (gamma_lo_i > "
                "gamma_safe_i):",
                s.infeasible.size(), s.free_nodes);
    for (size_t k = 0; k < s.infeasible.size() && k < 8; ++k)
      std::printf(" node %d (dt < %s)", s.infeasible[k], g5(s.infeasible_dt[k]).c_str());
    std::printf("%s\n", s.infeasible.size() > 8 ? " ..." : "");
  }
  if (s.compressed_springs > 0)
    std::printf("                      %s in compression: K may not be positive "
                "semi-definite; the safe bound guarantees nothing here\n",
                plural(s.compressed_springs, "spring").c_str());
  if (!paper_step)
    std::printf("                      (%s)\n", safe_bound_scope(exact.integrator).c_str());
}

/// The answer first (core/analysis/answer.hpp): the exact verdict at the parameters, its
/// limits, and the safe bound where it applies to the integrator.
void print_answer_of(const Model& model, const State& state, const Params& p,
                     const ExactStability& exact, const std::string& where) {
  const SafeBoundSummary safe = safe_bound_summary(model, state.x, p.dt);
  const bool safe_applies = safe_bound_scope(p.integrator).empty();
  print_answer(exact_answer(exact, &p, safe_applies ? &safe : nullptr, where));
}

int run_parameters(const BoundsArgs& a) {
  if (!a.f.m_opt->count() || !a.f.kappa_opt->count() || !a.f.dt_opt->count())
    throw InputError("--m, --kappa and --dt are required without a scene");
  // Asked about one node's state (--v, --force): that answer, and no table of the system at
  // rest, whose eq. 6 (v = 0: inf) would contradict it.
  if (!a.v.empty() || !a.force.empty()) {
    print_paper_lines(a);
    std::printf("(the system's criteria at rest: the same command without --v and --force)\n");
    return 0;
  }
  Params p;
  p.m = a.f.m;
  p.kappa = a.f.kappa;
  p.dt = a.f.dt;
  p.gamma = a.f.gamma_opt->count() ? a.f.gamma : lower_bound(a.f.m, a.f.kappa);
  if (a.f.zeta_opt->count()) p.gamma = gamma_of_zeta(a.f.zeta, p);  // every scale is 1 here
  if (a.f.integrator_opt->count()) p.integrator = *parse_integrator(a.f.integrator);
  a.f.apply_damping(p);
  const bool two = a.system == "two-node";
  const Model model = two ? two_node_system(p) : single_node_system(p);
  if (const auto why = magnitude_problem(model, p.dt)) throw InputError(*why);
  const State rest = rest_state(model);
  const ExactStability exact = exact_stability(model, rest.x, p);
  print_answer_of(model, rest, p, exact, "at rest");
  if (a.brief) return 0;
  print_paper_lines(a);
  std::printf("\nsystem       %s\n",
              two ? "two-node (paper sec. 2): node 0 fixed, node 1 on one spring of rest length "
                    "1 cm, no anchor; at rest"
                  : "single node on a zero-rest-length anchor (the linear oscillator); at rest");
  std::printf("parameters   m=%s kappa=%s gamma=%s%s (zeta=%s) dt=%s s integrator=%s\n",
              format_human(p.m).c_str(), format_human(p.kappa).c_str(),
              format_human(p.gamma).c_str(),
              a.f.gamma_opt->count() || a.f.zeta_opt->count() ? "" : " (= gamma_lo)",
              zeta_text(damping_ratio_range(model)).c_str(),
              format_human(p.dt).c_str(), to_string(p.integrator));
  print_safe_lines(model, rest, p, exact);
  print_damping_lines(model, rest, p, exact, kNoFactorBudget);
  print_criteria(all_criteria(model, rest, p, exact));
  return 0;
}

/// --worst N: the nodes with the smallest dt_safe_i and gamma_safe_i, and why.
void print_worst(const Model& model, const State& state, const Params& p, int count, bool json) {
  const WorstNodes w = worst_nodes(model, state.x, p.dt, count);
  auto rows = [&](const std::vector<WorstNode>& v) {
    std::string out;
    for (const WorstNode& n : v) {
      if (json) {
        out += std::string(out.empty() ? "" : ",") + "{\"node\":" + std::to_string(n.node) +
               ",\"dt_safe\":" + json_number(n.dt_safe) + ",\"gamma_safe\":" + json_number(n.gamma_safe) +
               ",\"mass\":" + json_number(n.mass) + ",\"stiffest\":" + json_number(n.stiffest) +
               ",\"shortest_edge\":" + json_number(n.shortest_edge) +
               ",\"degree\":" + std::to_string(n.degree) + ",\"cause\":" + json_string(n.cause) + "}";
      } else {
        char buf[512];
        std::snprintf(buf, sizeof buf, "  %7d %-12s %-12s %-10s %-10s %-10s %6d  %s\n", n.node,
                      format_human(n.dt_safe).c_str(), format_human(n.gamma_safe).c_str(),
                      format_human(n.mass).c_str(), format_human(n.stiffest).c_str(),
                      format_human(n.shortest_edge).c_str(), n.degree, n.cause.c_str());
        out += buf;
      }
    }
    return out;
  };
  if (json) {
    std::printf("{\"median_mass\":%s,\"median_kappa\":%s,\"median_edge\":%s,\"by_dt_safe\":[%s],"
                "\"by_gamma_safe\":[%s]}\n",
                json_number(w.median_mass).c_str(), json_number(w.median_kappa).c_str(),
                json_number(w.median_edge).c_str(), rows(w.by_dt).c_str(), rows(w.by_gamma).c_str());
    return;
  }
  std::printf("\nmedians      mass %s, spring stiffness %s, edge %s cm\n",
              format_human(w.median_mass).c_str(), format_human(w.median_kappa).c_str(),
              format_human(w.median_edge).c_str());
  const char* head = "     node dt_safe      gamma_safe   mass       stiffest   shortest   degree  cause\n";
  // Fewer free nodes than asked: say how many are shown, not the count asked for.
  auto shown = [&](size_t n) {
    return n < static_cast<size_t>(count)
               ? "the " + plural(static_cast<long long>(n), "free node") + " (" +
                     std::to_string(count) + " asked)"
               : "worst " + std::to_string(count);
  };
  std::printf("%s by dt_safe_i (at gamma_i):\n%s%s", shown(w.by_dt.size()).c_str(), head,
              rows(w.by_dt).c_str());
  std::printf("%s by gamma_safe_i (at dt = %s s):\n%s%s", shown(w.by_gamma.size()).c_str(),
              format_human(p.dt).c_str(), head, rows(w.by_gamma).c_str());
}

int run_scene(const BoundsArgs& a) {
  if (!a.v.empty() || !a.force.empty()) throw InputError("--v and --force need no scene");
  WaitNote note("bounds");  // a wait over 2 s is said on stderr, stage by stage
  note.stage("reading the scene");
  SceneSpec scene = load_scene_arg(a.scene);
  Params p = scene.params;
  StopRules unused_rules;
  a.f.apply(p, unused_rules);
  resolve_zeta(scene.model, p);
  require_magnitudes(scene.model, p);
  p.policy = DampingPolicy::fixed;  // the user's gamma is what is judged
  const std::string name = scene.name.empty() ? a.scene : scene.name;
  if (a.json && a.worst == 0) {  // the baseline `diff` reads: the limits at rest, as JSON
    if (a.after > 0 || a.equilibrium)
      throw InputError("--json writes the limits at rest (the baseline diff reads): drop " +
                       std::string(a.after > 0 ? "--after" : "--equilibrium"));
    ExactOptions options;
    options.threads = 0;
    options.max_factor_flops = a.factor_budget * 1e9;
    note.stage("the limits at rest (" + scene_counts(scene.model) + ")");
    LimitsSnapshot s = limits_snapshot(scene, p, options);
    if (s.scene.empty()) s.scene = name;
    write_limits_json(std::cout, s);
    std::cout.flush();
    return 0;
  }
  note.stage("building the model (" + scene_counts(scene.model) + ")");
  Session session(std::move(scene), p, StopRules{});
  for (int k = 0; k < a.after && session.running(); ++k) {
    if (k % 64 == 0) note.stage("stepping to --after", k, a.after);
    session.step_once();
  }
  const Model& model = session.model();
  State state = a.after > 0 ? session.state() : rest_state(model);
  Equilibrium held;
  if (a.equilibrium) {
    EquilibriumOptions eo;
    eo.max_factor_flops = a.factor_budget * 1e9;
    note.stage("static equilibrium (Newton's method)");
    try {
      held = static_equilibrium(model, eo);
    } catch (const FactorisationOverBudget& over) {
      throw std::runtime_error("--equilibrium: " + equilibrium_over_budget(over) +
                               " (--factor-budget)");
    }
    if (!held.converged) throw std::runtime_error("--equilibrium: " + no_equilibrium(held));
    state.x = held.x;
  }
  if (a.worst > 0 && a.json) {
    print_worst(model, state, p, a.worst, true);
    return 0;
  }
  ExactOptions options;
  options.threads = 0;  // a big mesh's Lanczos products on every CPU (the same bits)
  options.max_factor_flops = a.factor_budget * 1e9;
  note.stage("exact linear analysis (" + scene_counts(model.spec(), false) +
             "; --factor-budget " + format_human(a.factor_budget) + " GFlop per factorisation)");
  const ExactStability exact = exact_stability(model, state.x, p, options);
  print_answer_of(model, state, p, exact,
                  a.after > 0        ? "after " + plural(state.iteration, "step")
                  : a.equilibrium ? "at the static equilibrium"
                                  : "at rest");
  if (a.brief) return 0;
  std::printf("scene        %s (%s)\n", name.c_str(), scene_counts(model.spec()).c_str());
  std::printf("parameters   m=%s kappa=%s gamma=%s (zeta=%s) dt=%s s integrator=%s (gamma_i = "
              "gamma * gamma_scale_i, m_i = m * mass_scale_i)\n",
              format_human(p.m).c_str(), format_human(p.kappa).c_str(),
              format_human(p.gamma).c_str(), zeta_text(damping_ratio_range(model)).c_str(),
              format_human(p.dt).c_str(),
              to_string(p.integrator));
  if (a.after > 0) {
    std::printf("state        after %s of the scene's perturbed run (policy fixed)\n",
                plural(state.iteration, "step").c_str());
  } else if (a.equilibrium) {
    std::printf(
        "state        static equilibrium under the scene's forces and rest lengths (v = "
        "0; %s): the linearisation point of the exact analysis\n",
        equilibrium_summary(held).c_str());
  } else {
    std::printf("state        rest (x = X, v = 0): the linearisation point of the exact analysis\n");
    const NetForce n = net_force(model, state.x);
    if (!n.balanced())  // external forces, or rest lengths other than the rest geometry's
      std::printf("note         %s, so a run leaves it; --equilibrium analyses where a damped "
                  "run settles\n",
                  rest_not_in_equilibrium(n).c_str());
  }
  std::printf("exact method %s\n", to_string(exact.method));
  if (!exact.computed())
    std::printf("             %s (--factor-budget)%s\n", exact.over_budget_reason().c_str(),
                safe_bound_scope(p.integrator).empty()
                    ? "; the safe bound below still holds"
                    : "");
  print_safe_lines(model, state, p, exact);
  print_damping_lines(model, state, p, exact, options.max_factor_flops);
  note.stage("the other criteria");
  if (a.worst > 0) print_worst(model, state, p, a.worst, false);
  print_criteria(all_criteria(model, state, p, exact));
  return 0;
}

int run(const BoundsArgs& a) {
  if (a.scene.empty() && a.worst > 0) throw InputError("--worst needs a SCENE");
  if (a.json && a.scene.empty()) throw InputError("--json needs a SCENE");
  return a.scene.empty() ? run_parameters(a) : run_scene(a);
}

std::function<int()> setup(CLI::App& root) {
  auto a = std::make_shared<BoundsArgs>();
  CLI::App* cmd = root.add_subcommand(
      "bounds",
      "Print the paper's damping bounds: the lower bound 2*sqrt(m*kappa) (eq. 5) and, given a "
      "velocity and force, the upper bound |v*m/dt+F|/|v| (eq. 6) and the runtime check "
      "(sec. 5); then every stability criterion (paper, Delingette, Provot, Kacic-Alesic, exact "
      "linear) with its value and verdict, for the two-node system or for a SCENE.");
  cmd->add_option("scene", a->scene,
                  "scene file (.toml) or shipped scene name; without it --m --kappa --dt are "
                  "required and the two-node system (or --system single-node) is analysed");
  a->f.m_opt = cmd->add_option("--m", a->f.m, "node mass (mass unit)")->check(finite_positive());
  a->f.kappa_opt = cmd->add_option("--kappa", a->f.kappa, "stiffness (mass unit/s^2)")
                     ->check(finite_positive());
  a->f.dt_opt = cmd->add_option("--dt", a->f.dt, "time step (s)")->check(finite_positive());
  cmd->add_option("--v", a->v, "node velocity x,y,z (cm/s)");
  cmd->add_option("--force", a->force, "internal (spring) force on the node x,y,z (mass unit cm/s^2)");
  a->f.gamma_opt = cmd->add_option("--gamma", a->f.gamma,
                                 "a damping to test against the bounds (mass unit/s); default "
                                 "the scene's, or gamma_lo without a scene")
                     ->check(finite_non_negative());
  a->f.zeta_opt = add_zeta_option(cmd, a->f.zeta, a->f.gamma_opt);
  a->f.integrator_opt =
      cmd->add_option("--integrator", a->f.integrator, "integrator whose exact limits are shown")
          ->check(CLI::IsMember(integrator_names()));
  cmd->add_option("--system", a->system, "without a scene: two-node (default) or single-node")
      ->check(CLI::IsMember({"two-node", "single-node"}));
  cmd->add_option("--after", a->after,
                  "with a scene: analyse the state after this many steps of its perturbed run "
                  "(default 0: the rest state)")
      ->check(whole_range(0, 100000000));
  cmd->add_flag("--equilibrium", a->equilibrium,
                "with a scene: analyse at its static equilibrium under its external forces and "
                "rest lengths (Newton's method; where a damped run settles) instead of at rest")
      ->excludes("--after");
  cmd->add_option("--worst", a->worst,
                  "with a scene: the N nodes with the smallest dt_safe_i and the N with the "
                  "smallest gamma_safe_i, each with its mass, stiffest spring, shortest "
                  "edge, degree and the cause in words")
      ->check(whole_range(1, 1000000));
  cmd->add_flag("--json", a->json,
                "with a scene: its limits at rest as JSON only, the baseline `diff` reads (what "
                "diff --save writes); with --worst: the worst nodes as one JSON object only");
  add_brief_flag(cmd, a->brief);
  a->f.add_damping_to(cmd);
  add_factor_budget_option(cmd, a->factor_budget);
  return [a] { return run(*a); };
}

const bool registered = register_command("bounds", setup);

}  // namespace
}  // namespace dampbound::app::cmd_bounds
