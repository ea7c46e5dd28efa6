#include "core/io/report.hpp"

#include <ostream>
#include <sstream>

#include "core/io/format.hpp"

namespace dampbound {

namespace {
/// Quotes a CSV field when it holds a comma, a quote or a line break (LF or CR, RFC 4180).
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}
/// SPEC 8's fields: the rule, then first_entry, left_at, settled_at, null where none (under
/// the first-entry rule the run stops at the entry, so left_at and settled_at are never seen).
std::string band_json(const StopRules& rules, const RunResult& r) {
  const auto field = [](const char* key, int it) {
    return std::string(",\"") + key + "\":" + (it > 0 ? std::to_string(it) : "null");
  };
  return std::string(",\"rule\":") + json_string(to_string(rules.rule)) +
         field("first_entry", r.first_entry) + field("left_at", r.left_at) +
         field("settled_at", r.settled_at);
}
}  // namespace

void write_trace_csv(std::ostream& out, const std::vector<StepSample>& trace,
                     const std::string& run_label, bool header) {
  const std::string prefix = run_label.empty() ? "" : csv_field(run_label) + ",";
  if (header)
    out << (run_label.empty() ? "" : "run,") << "iteration,time,displacement,lower_bound,upper_bound,gamma,gamma_effective,"
         "zeta,zeta_effective,max_displacement,violating,unstabilisable,clamped,zero_length_springs,"
         "safe_bound,unguaranteed,compressed_springs\n";
  for (const StepSample& s : trace)
    out << prefix << s.iteration << ',' << format_number(s.time) << ','
        << format_number(s.watched.displacement) << ',' << format_number(s.watched.lower) << ','
        << format_number(s.watched.upper) << ',' << format_number(s.watched.gamma) << ','
        << format_number(s.watched.gamma_eff) << ','
        << format_number(damping_ratio(s.watched.gamma, s.watched.lower)) << ','
        << format_number(damping_ratio(s.watched.gamma_eff, s.watched.lower)) << ','
        << format_number(s.max_displacement) << ','
        << s.violating << ',' << s.unstabilisable << ',' << s.clamped << ','
        << s.zero_length_springs << ',' << format_number(s.watched.safe) << ','
        << s.unguaranteed << ',' << s.compressed_springs << '\n';
}

std::string verdict_short(const RunResult& r) {
  const std::string left = r.left_at > 0 ? ", left at " + std::to_string(r.left_at) : "";
  switch (r.outcome) {
    case Outcome::running:
      return r.left_at > 0 ? "running (entered at " + std::to_string(r.first_entry) + left + ")"
                           : "running";
    case Outcome::restored:
      return "restored at " + std::to_string(r.iterations);
    case Outcome::diverged:
      return "diverged at " + std::to_string(r.iterations);
    case Outcome::not_restored:
      return "not restored at " + std::to_string(r.iterations);
    case Outcome::settled:
      return "settled at " + std::to_string(r.settled_at);
    case Outcome::not_settled:
      return "not settled at " + std::to_string(r.iterations) +
             (r.first_entry > 0 ? " (entered at " + std::to_string(r.first_entry) + left + ")"
                                : "");
  }
  return "?";
}

std::string verdict_text(const RunResult& r, const StopRules& rules) {
  const std::string band = "the " + format_number(100 * rules.restore_fraction) + "% band";
  std::string history;  // "entered the 1% band at K, left it at L"
  if (r.first_entry > 0) history = "entered " + band + " at " + std::to_string(r.first_entry);
  if (r.left_at > 0) history += ", left it at " + std::to_string(r.left_at);
  const std::string checked = ", checked to " + std::to_string(rules.max_iterations);
  const auto aside = [&](const std::string& what) {
    return history.empty() ? what : what + " (" + history + ")";
  };
  switch (r.outcome) {
    case Outcome::running:
      if (r.left_at > 0 && r.below_since > r.left_at)
        history += ", back in since " + std::to_string(r.below_since);
      return history.empty() ? "running" : "running: " + history;
    case Outcome::restored:
      return "restored at " + std::to_string(r.iterations) + " (first entry into " + band +
             ", the paper's rule)";
    case Outcome::not_restored:
      return "not restored" + checked + " (the paper's rule)";
    case Outcome::diverged:
      return aside("diverged at " + std::to_string(r.iterations));
    case Outcome::settled: {
      // SPEC 8's early stop (docs/settled.md): a run stopped by the proof says where.
      const std::string to = r.iterations > 0 && r.iterations < rules.max_iterations
                                 ? ", proven at " + std::to_string(r.iterations) +
                                       " to stay to " + std::to_string(rules.max_iterations)
                                 : checked;
      // A run that settled at its first entry says no more; one that left first says when.
      return r.left_at > 0 ? aside("settled at " + std::to_string(r.settled_at) + to)
                           : "settled at " + std::to_string(r.settled_at) + to;
    }
    case Outcome::not_settled:
      return history.empty() ? "not settled" + checked + " (never entered " + band + ")"
                             : aside("not settled" + checked);
  }
  return "?";
}

std::string zeta_text(const DampingRatioRange& z) {
  if (std::isnan(z.min)) return "none";
  return format_human_range(z.min, z.max);
}

std::string result_json(const std::string& scene, const Params& p, const StopRules& rules,
                        int watched, const RunResult& r, const DampingRatioRange* zeta) {
  std::ostringstream os;
  os << "{\"scene\":" << json_string(scene) << ",\"m\":" << json_number(p.m)
     << ",\"kappa\":" << json_number(p.kappa) << ",\"gamma\":" << json_number(p.gamma);
  if (zeta) os << ",\"zeta_min\":" << json_number(zeta->min) << ",\"zeta_max\":" << json_number(zeta->max);
  os     << ",\"dt\":" << json_number(p.dt) << ",\"policy\":" << json_string(to_string(p.policy))
     << ",\"factor\":" << json_number(p.factor)
     << ",\"integrator\":" << json_string(to_string(p.integrator))
     // SPEC 10's damping and the band: every parameter that shaped the run.
     << ",\"kd\":" << json_number(p.kd) << ",\"rayleigh_mass\":" << json_number(p.rayleigh_mass)
     << ",\"rayleigh_stiffness\":" << json_number(p.rayleigh_stiffness)
     << ",\"reference\":" << json_number(rules.reference)
     << ",\"restore_fraction\":" << json_number(rules.restore_fraction)
     << ",\"diverge_factor\":" << json_number(rules.diverge_factor)
     << ",\"max_iterations\":" << rules.max_iterations << ",\"watched\":" << watched
     << ",\"outcome\":" << json_string(to_string(r.outcome)) << ",\"iterations\":" << r.iterations
     << band_json(rules, r)
     << ",\"time\":" << json_number(r.time)
     << ",\"max_displacement\":" << json_number(r.max_displacement)
     << ",\"violations\":" << r.violations << ",\"unstabilisable\":" << r.unstabilisable
     << ",\"clamped\":" << r.clamped << ",\"zero_length_springs\":" << r.zero_length_springs
     << ",\"unguaranteed\":" << r.unguaranteed
     << ",\"compressed_springs\":" << r.compressed_springs << "}";
  return os.str();
}

}  // namespace dampbound
