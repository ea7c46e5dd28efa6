#include "core/protocol.hpp"

namespace dampbound {

const char* to_string(Outcome o) {
  switch (o) {
    case Outcome::running: return "running";
    case Outcome::restored: return "restored";
    case Outcome::diverged: return "diverged";
    case Outcome::not_restored: return "not_restored";
    case Outcome::settled: return "settled";
    case Outcome::not_settled: return "not_settled";
  }
  return "?";
}

std::array<Outcome, 3> final_outcomes(StopRule rule) {
  if (rule == StopRule::settled) return {Outcome::settled, Outcome::diverged, Outcome::not_settled};
  return {Outcome::restored, Outcome::diverged, Outcome::not_restored};
}

const char* to_string(StopRule r) {
  return r == StopRule::settled ? "settled" : "first-entry";
}

std::optional<StopRule> parse_stop_rule(const std::string& text) {
  for (StopRule r : {StopRule::first_entry, StopRule::settled})
    if (text == to_string(r)) return r;
  return std::nullopt;
}

Outcome judge(const StopRules& rules, const StepStats& stats) {
  StopRules paper = rules;
  paper.rule = StopRule::first_entry;
  BandHistory band;
  return judge_band(paper, band, stats.iteration, stats.max_displacement, stats.finite);
}

Outcome judge_band(const StopRules& rules, BandHistory& band, int iteration,
                   double max_displacement, bool finite) {
  // The comparisons are written so that a NaN falls to diverged, never below the threshold.
  if (!finite || !(max_displacement <= rules.diverge_factor * rules.reference))
    return Outcome::diverged;
  const bool below = max_displacement < rules.restore_fraction * rules.reference;
  if (below) {
    if (band.first_entry == 0) band.first_entry = iteration;
    if (band.below_since == 0) band.below_since = iteration;
  } else {
    if (band.first_entry != 0 && band.left_at == 0) band.left_at = iteration;
    band.below_since = 0;
  }
  if (rules.rule == StopRule::first_entry) {
    if (below) return Outcome::restored;
    return iteration >= rules.max_iterations ? Outcome::not_restored : Outcome::running;
  }
  // SPEC 8: no proof that a run below the threshold stays there, so it steps to the limit.
  if (iteration < rules.max_iterations) return Outcome::running;
  return below ? Outcome::settled : Outcome::not_settled;
}

void accumulate(RunResult& r, const StepStats& st, const StopRules& rules) {
  r.violations += st.violating;
  r.unstabilisable += st.unstabilisable;
  r.clamped += st.clamped;
  r.zero_length_springs += st.zero_length_springs;
  r.unguaranteed += st.unguaranteed;
  r.compressed_springs += st.compressed_springs;
  r.max_displacement = st.max_displacement;
  r.time = st.time;
  if (r.outcome == Outcome::running) {
    r.iterations = st.iteration;
    BandHistory band{r.first_entry, r.left_at, r.below_since};
    r.outcome = judge_band(rules, band, st.iteration, st.max_displacement, st.finite);
    r.first_entry = band.first_entry;
    r.left_at = band.left_at;
    r.below_since = band.below_since;
    if (r.outcome == Outcome::settled) r.settled_at = band.below_since;
  }
}

}  // namespace dampbound
