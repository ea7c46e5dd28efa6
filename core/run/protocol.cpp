#include "dampbound/run/protocol.hpp"

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
