#include "guarantee_checks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <sstream>

#include "core/analysis/linear_stability_exact.hpp"
#include "core/analysis/substeps.hpp"
#include "core/analysis/suggest.hpp"
#include "core/physics/integrate.hpp"
#include "core/physics/safe_bound.hpp"
#include "core/sweep/runner.hpp"
#include "dampbound/physics/step.hpp"
#include "dampbound/run/scene.hpp"
#include "dense_reference.hpp"

namespace dampbound::hunt {
namespace {

// A radius up to 1 + kBounded is bounded (marginal modes sit at 1 within rounding); above
// 1 + kGrows it grows; in between the dense eigensolver cannot tell, and nothing is judged.
constexpr double kBounded = 1e-7, kGrows = 1e-6;

std::string num(double x) {
  std::ostringstream o;
  o.precision(10);
  o << x;
  return o.str();
}

Params with(Params p, double gamma, double dt) {
  p.gamma = gamma;
  p.dt = dt;
  return p;
}

double radius(const Case& c, const Params& p) {
  return dense_radius(dense_system(c.spec, p), p.integrator, p.dt);
}

/// A claim "stable at p": the dense radius must not grow.
void stable_at(const Case& c, const Params& p, Tally& t, const std::string& claim) {
  const double rho = radius(c, p);
  t.expect(rho <= 1 + kGrows, c.what,
           claim + " (gamma " + num(p.gamma) + ", dt " + num(p.dt) + "): dense radius " + num(rho));
}

/// A limit's other side "unstable at p": the dense radius must exceed 1 (a limit set low is a
/// wrong answer too, if a safe one).
void unstable_at(const Case& c, const Params& p, Tally& t, const std::string& claim) {
  const double rho = radius(c, p);
  if (rho > 1 + kBounded && rho <= 1 + kGrows) return;  // undecidable here
  t.expect(rho > 1 + kBounded, c.what,
           claim + " (gamma " + num(p.gamma) + ", dt " + num(p.dt) + "): dense radius " + num(rho));
}

/// max_i |x_i - X_i| over `steps` steps of the real step() from a small push of every node
/// (position and velocity), relative to the push.
double run_growth(const Case& c, const Params& p, int steps) {
  const Model model = compile_model(c.spec, p);
  State s = rest_state(model);
  Draw d(c.seed ^ 0x5bd1e995ULL);
  double scale = 0;
  for (const Vec3& x : c.spec.rest) scale = std::max(scale, x.norm());
  const double push = 1e-7 * std::max(scale, 1e-300);
  // Positions and velocities both: a position alone is the z = 1 eigenvector of a zero mode
  // and never excites its velocity's decay factor, which damping can make grow (RK4 at c h >
  // 2.785).
  const double time_unit = std::sqrt(p.m) / std::sqrt(p.kappa);
  for (size_t i = 0; i < s.x.size(); ++i)
    if (!c.spec.fixed[i]) {
      s.x[i] += push * Vec3(d.uniform(-1, 1), d.uniform(-1, 1), d.uniform(-1, 1));
      s.v[i] += (push / time_unit) * Vec3(d.uniform(-1, 1), d.uniform(-1, 1), d.uniform(-1, 1));
    }
  StepWorkspace ws;
  double start = 0;
  for (size_t i = 0; i < s.x.size(); ++i) start = std::max(start, displacement(c.spec, s, int(i)));
  double end = 0;
  for (int k = 0; k < steps; ++k) step(model, p, s, ws);
  for (size_t i = 0; i < s.x.size(); ++i) {
    const double u = displacement(c.spec, s, int(i));
    end = std::max(end, std::isfinite(u) ? u : std::numeric_limits<double>::infinity());
  }
  return start > 0 ? end / start : 0;
}

/// The dt limit by runs: at 1.02x the push grows past 100x in the steps the dense radius needs
/// for 1e9 (when that is at most 20000; the push is not all in the growing mode), and at
/// 0.98x it stays below 1000x over as many.
void runs_at_limit(const Case& c, double dt_max, Tally& t) {
  const Params hi = with(c.params, c.params.gamma, 1.02 * dt_max);
  const double rho = radius(c, hi);
  if (!(rho > 1 + 1e-4)) return;
  const int steps = static_cast<int>(std::ceil(std::log(1e9) / std::log(rho)));
  if (steps > 20000) return;
  const double grown = run_growth(c, hi, steps);
  t.expect(grown > 1e2, c.what, "run at 1.02x dt_max " + num(dt_max) + " grew only " + num(grown) +
                                    "x in " + std::to_string(steps) + " steps");
  const double kept = run_growth(c, with(c.params, c.params.gamma, 0.98 * dt_max), steps);
  t.expect(kept < 1e3, c.what, "run at 0.98x dt_max " + num(dt_max) + " grew " + num(kept) +
                                   "x in " + std::to_string(steps) + " steps");
}

void exact_claims(const Case& c, const ExactStability& e, Tally& t) {
  const Params& p = c.params;
  const bool estimate = e.method == ExactMethod::frozen_estimate;
  const bool decided = e.method != ExactMethod::damped_radius || e.radius_converged;
  if (e.stable) {
    stable_at(c, p, t, std::string("called stable (") + to_string(e.method) + ")");
  } else if (decided && !estimate) {
    const double rho = radius(c, p);
    t.expect(rho > 1 - kBounded, c.what,
             std::string("called unstable (") + to_string(e.method) + "), dense radius " + num(rho));
  }
  // Every number printed beside a verdict is a number.
  t.expect(!(e.stable && std::isnan(e.spectral_radius) && std::isnan(e.index) &&
             e.method != ExactMethod::unconditional && !integrator_traits(e.integrator).implicit),
           c.what, "a verdict without a number behind it");
  if (std::isfinite(e.dt_max) && e.dt_max > 0) {
    stable_at(c, with(p, p.gamma, 0.98 * e.dt_max), t, "below 0.98x the dt limit " + num(e.dt_max));
    if (!estimate) {
      unstable_at(c, with(p, p.gamma, 1.02 * e.dt_max), t, "above 1.02x the dt limit " + num(e.dt_max));
      runs_at_limit(c, e.dt_max, t);
    }
  }
  if (std::isfinite(e.gamma_hi) && e.gamma_hi > 0 && e.gamma_hi > e.gamma_lo) {
    const double inside = std::max(0.98 * e.gamma_hi, 0.5 * (e.gamma_lo + e.gamma_hi));
    stable_at(c, with(p, inside, p.dt), t, "inside the gamma interval [" + num(e.gamma_lo) + ", " +
                                               num(e.gamma_hi) + ")");
    if (!estimate)
      unstable_at(c, with(p, 1.02 * e.gamma_hi, p.dt), t,
                  "above 1.02x the gamma interval's top " + num(e.gamma_hi));
  }
}

void safe_claims(const Case& c, const Model& model, const ExactStability& e, Tally& t) {
  if (!integrator_traits(c.params.integrator).paper_step || e.indefinite) return;
  const Params& p = c.params;
  const SafeBoundSummary s = safe_bound_summary(model, c.spec.rest, p.dt);
  if (std::isfinite(s.dt_safe) && s.dt_safe > 0) {
    if (std::isfinite(e.dt_max))
      t.expect(s.dt_safe <= e.dt_max * (1 + 1e-9), c.what,
               "safe dt " + num(s.dt_safe) + " above the exact dt limit " + num(e.dt_max));
    stable_at(c, with(p, p.gamma, 0.999 * s.dt_safe), t, "below the safe dt " + num(s.dt_safe));
  }
  if (std::isfinite(s.gamma_safe) && s.gamma_safe > 0) {
    if (std::isfinite(e.gamma_hi))
      t.expect(s.gamma_safe <= e.gamma_hi * (1 + 1e-9), c.what,
               "safe gamma " + num(s.gamma_safe) + " above the exact gamma limit " + num(e.gamma_hi));
    stable_at(c, with(p, 0.999 * s.gamma_safe, p.dt), t, "below the safe gamma " + num(s.gamma_safe));
  }
}

SceneSpec scene_of(const Case& c) {
  SceneSpec scene;
  scene.name = "hunted";
  scene.model = c.spec;
  scene.params = c.params;
  for (size_t i = 0; i < c.spec.rest.size(); ++i)
    if (!c.spec.fixed[i]) {
      scene.perturbations.push_back({int(i), Vec3(0, 1e-3, 0), Vec3::Zero()});
      scene.watched = int(i);
      break;
    }
  return scene;
}

void suggest_claims(const Case& c, Tally& t) {
  const SceneSpec scene = scene_of(c);
  SuggestOptions quiet;
  quiet.verify = false;
  const Params& p = c.params;
  const DampingSuggestion d = suggest_damping(scene, p, scene.rules, quiet);
  if (integrator_traits(p.integrator).paper_step && std::isfinite(d.safe_max) && d.safe_max > 0) {
    if (std::isfinite(d.gamma_max) && !d.proved_only)
      t.expect(d.safe_max <= d.gamma_max * (1 + 1e-9), c.what,
               "suggest's safe gamma " + num(d.safe_max) + " above its gamma_max " + num(d.gamma_max));
    stable_at(c, with(p, 0.999 * d.safe_max, p.dt), t, "below suggest's safe gamma " + num(d.safe_max));
  }
  if (!d.empty && std::isfinite(d.gamma_max) && d.gamma_max > 0)
    stable_at(c, with(p, std::max(d.gamma_min, 0.99 * d.gamma_max), p.dt), t,
              "inside suggest's damping range [" + num(d.gamma_min) + ", " + num(d.gamma_max) + ")");
  const StepSuggestion s = suggest_step(scene, p, scene.rules, quiet);
  if (std::isfinite(s.dt_all) && s.dt_all > 0)
    stable_at(c, with(p, p.gamma, 0.999 * s.dt_all), t, "suggest's largest dt " + num(s.dt_all));
  if (integrator_traits(p.integrator).paper_step && std::isfinite(s.dt_safe) && s.dt_safe > 0)
    stable_at(c, with(p, p.gamma, 0.999 * s.dt_safe), t, "suggest's safe dt " + num(s.dt_safe));
  const double frame = p.dt * 3.7;
  const SubstepSuggestion n = suggest_substeps(scene, p, scene.rules, frame, quiet);
  if (n.exact.n > 0)
    stable_at(c, with(p, p.gamma, frame / n.exact.n), t, substeps_text(n.exact.n) + " by the exact limit");
  if (n.safe.n > 0 && integrator_traits(p.integrator).paper_step)
    stable_at(c, with(p, p.gamma, frame / n.safe.n), t, substeps_text(n.safe.n) + " by the safe bound");
}

}  // namespace

void hunt_scene(const Case& c, Tally& t) {
  ++t.scenes;
  if (t.verbose) std::printf("%s\n", c.what.c_str());
  try {
    const Model model = compile_model(c.spec, c.params);
    const ExactStability e = exact_stability(model, c.spec.rest, c.params);
    exact_claims(c, e, t);
    safe_claims(c, model, e, t);
    suggest_claims(c, t);
  } catch (const std::exception& ex) {
    t.expect(false, c.what, std::string("threw: ") + ex.what());
  }
}

void hunt_sweep(std::uint64_t seed, Tally& t) {
  ++t.sweeps;
  Draw d(seed);
  SweepRequest r;
  r.scene = paper_plane_scene(5);
  r.scene.rules.max_iterations = 150 + d.below(150);
  r.scene.rules.rule = d.chance(0.5) ? StopRule::settled : StopRule::first_entry;
  SweepSpec& s = r.spec;
  s.rules = r.scene.rules;
  s.policy = kPolicies[d.below(5)];
  s.m = parse_axis("--m", "0.001,0.002", AxisDomain::positive);
  s.kappa = parse_axis("--kappa", "0.001,0.004", AxisDomain::positive);
  s.gamma_mode = GammaMode::absolute;
  s.gamma = parse_axis("--gamma", "0.0005,0.004,0.03", AxisDomain::non_negative);
  s.dt = parse_axis("--dt", d.chance(0.5) ? "0.05" : "0.05,0.2", AxisDomain::positive);
  s.factor = parse_axis("--factor", "1,1.05", AxisDomain::positive);
  if (d.chance(0.4)) s.kd = parse_axis("--kd", "0,0.002", AxisDomain::non_negative);
  if (d.chance(0.3)) s.rayleigh_mass = parse_axis("--rayleigh-mass", "0,0.5", AxisDomain::non_negative);
  if (d.chance(0.3))
    s.rayleigh_stiffness = parse_axis("--rayleigh-stiffness", "0,0.01", AxisDomain::non_negative);
  const std::string where = "sweep seed " + std::to_string(seed) + " (policy " +
                            to_string(s.policy) + ", " + to_string(s.rules.rule) + ")";
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("hunter-" + std::to_string(seed));
  std::filesystem::create_directories(dir);
  try {
    r.threads = 1;
    r.output = (dir / "classes.csv").string();
    const SweepReport classes = run_sweep(r);
    r.spec.allow_similarity = false;
    r.use_kernel = false;
    r.output = (dir / "alone.csv").string();
    const SweepReport alone = run_sweep(r);
    t.expect(classes.rows.size() == alone.rows.size(), where, "row counts differ");
    for (size_t k = 0; k < std::min(classes.rows.size(), alone.rows.size()); ++k) {
      const SweepRow &a = classes.rows[k], &b = alone.rows[k];
      t.expect(a.outcome == b.outcome && a.iterations == b.iterations &&
                   a.settled_at == b.settled_at && a.max_displacement == b.max_displacement,
               where, "trial " + std::to_string(a.trial) + " (m " + num(a.m) + " kappa " +
                          num(a.kappa) + " gamma " + num(a.gamma) + " dt " + num(a.dt) + "): " +
                          to_string(a.outcome) + " at " + std::to_string(a.iterations) +
                          " in its class, " + to_string(b.outcome) + " at " +
                          std::to_string(b.iterations) + " alone");
    }
  } catch (const std::exception& ex) {
    t.expect(false, where, std::string("threw: ") + ex.what());
  }
  std::filesystem::remove_all(dir);
}

}  // namespace dampbound::hunt
