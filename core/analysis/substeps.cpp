#include "core/analysis/substeps.hpp"

#include <algorithm>
#include <cmath>

#include "core/analysis/linear_stability_exact.hpp"
#include "core/physics/safe_bound.hpp"

namespace dampbound {

int substeps_below(double frame_dt, double limit) {
  if (!(limit > 0) || !(frame_dt > 0)) return 0;
  if (std::isinf(limit)) return 1;
  const double q = std::floor(frame_dt / limit);
  if (q >= kMaxSubsteps) return 0;
  int n = static_cast<int>(q) + 1;
  // frame_dt / limit rounds: step to the exact fewest n in the doubles the run will use.
  while (n > 1 && frame_dt / (n - 1) < limit) --n;
  while (!(frame_dt / n < limit) && n < kMaxSubsteps) ++n;
  return frame_dt / n < limit ? n : 0;
}

int verify_iterations(int max_iterations, double horizon, double dt) {
  const double want = std::ceil(horizon / dt);
  const double most = static_cast<double>(kVerifySpan) * max_iterations;
  if (!(want > max_iterations)) return max_iterations;
  return static_cast<int>(std::min(want, most));
}

std::string substeps_text(int n) {
  return std::to_string(n) + (n == 1 ? " substep" : " substeps");
}

const SubstepCount* SubstepSuggestion::answer() const {
  if (exact.verified()) return &exact;
  if (by_running.verified()) return &by_running;
  if (safe.verified()) return &safe;
  return nullptr;
}

namespace {

std::string count_label(int n, const char* what) {
  return substeps_text(n) + " (" + what + ")";
}

class Runner {
 public:
  Runner(const SceneSpec& scene, const Params& params, const StopRules& rules,
         const SuggestOptions& options)
      : scene_(scene), params_(params), rules_(rules), options_(options),
        horizon_(rules.max_iterations * scene.params.dt) {}

  void stage(const std::string& what) {
    if (options_.progress && !options_.progress(done_, 0, what)) throw SuggestCancelled();
    ++done_;
  }

  void run(SubstepCount& c, double frame_dt, const char* what) {
    c.dt = frame_dt / c.n;
    const std::string label = count_label(c.n, what);
    stage("verifying " + label);
    Params at = params_;
    at.dt = c.dt;
    StopRules rules = rules_;
    rules.max_iterations = verify_iterations(rules_.max_iterations, horizon_, c.dt);
    c.run = verify_run(scene_, at, rules, label);
    c.ran = true;
  }

 private:
  const SceneSpec& scene_;
  const Params& params_;
  const StopRules& rules_;
  const SuggestOptions& options_;
  const double horizon_;  ///< the scene's simulated time: its iteration limit at its dt (s)
  int done_ = 0;
};

// The exact count did not settle. Counts grow by a quarter (at least one) until one settles
// (or the safe count, when it settled, closes the bracket at once), then the bracket between
// the largest count that did not settle and the smallest that did is bisected; at most
// kMaxSearchRuns runs, over counts up to kSearchSpan times the exact count. Not every count in
// a gap is run, so the result is the fewest found.
void search_by_running(SubstepSuggestion& s, Runner& runner) {
  int lo = s.exact.n, hi = 0;  // lo did not settle; hi settled
  const long span = std::min<long>(kMaxSubsteps, static_cast<long>(kSearchSpan) * s.exact.n);
  SubstepCount found;
  if (s.safe.verified() && s.safe.n > lo) {
    hi = s.safe.n;
    found = s.safe;
  }
  auto attempt = [&](int n) {
    SubstepCount c;
    c.n = n;
    runner.run(c, s.frame_dt, "found by running");
    ++s.search_runs;
    if (c.verified()) {
      hi = n;
      found = c;
    } else {
      lo = n;
    }
  };
  while (!hi && s.search_runs < kMaxSearchRuns && lo < span)
    attempt(static_cast<int>(std::min(span, std::max(lo + 1L, std::lround(lo * 1.25 + 0.5)))));
  while (hi && hi - lo > 1 && s.search_runs < kMaxSearchRuns) attempt(lo + (hi - lo) / 2);
  s.failed_at_most = lo;
  if (hi) {
    s.by_running = found;
    s.by_running.limit = 0;
  }
}

}  // namespace

SubstepSuggestion suggest_substeps(const SceneSpec& scene, const Params& params,
                                   const StopRules& rules, double frame_dt,
                                   const SuggestOptions& options) {
  SubstepSuggestion s;
  s.frame_dt = frame_dt;
  Params p = params;
  p.dt = frame_dt;
  Runner runner(scene, p, rules, options);
  runner.stage("the exact limit and the safe bound");
  const Model model = compile_model(scene.model, p);
  const State rest = rest_state(model);
  ExactOptions only_limits;  // the count needs dt_max alone: no spectral radius
  only_limits.with_radius = false;
  only_limits.max_factor_flops = options.max_factor_flops;
  only_limits.threads = options.threads;
  only_limits.shared = options.shared;
  const ExactStability exact = exact_stability(model, rest.x, p, only_limits);
  s.exact.limit = exact.computed() ? exact.dt_max : 0;
  if (!exact.computed()) s.note = "exact limit not computed: " + exact.over_budget_reason();
  s.safe.limit = safe_bound_summary(model, rest.x, p.dt).dt_safe;
  for (SubstepCount* c : {&s.exact, &s.safe}) {
    c->n = substeps_below(frame_dt, c->limit);
    if (c->n > 0) c->dt = frame_dt / c->n;
  }
  if (!options.verify) return s;
  if (s.exact.n > 0) runner.run(s.exact, frame_dt, "exact limit");
  if (s.safe.n > 0) {
    if (s.safe.n == s.exact.n) {  // the same dt: the same run
      s.safe.run = s.exact.run;
      s.safe.run.label = count_label(s.safe.n, "safe bound");
      s.safe.ran = true;
    } else {
      runner.run(s.safe, frame_dt, "safe bound");
    }
  }
  if (s.exact.ran && !s.exact.verified()) search_by_running(s, runner);
  return s;
}

}  // namespace dampbound
