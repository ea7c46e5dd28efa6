#include "core/report.hpp"

#include <ostream>
#include <sstream>

#include "core/io.hpp"

namespace dampbound {

namespace {
/// Quotes a CSV field when it holds a comma, a quote or a newline.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}
}  // namespace

void write_trace_csv(std::ostream& out, const std::vector<StepStats>& trace,
                     const std::string& run_label, bool header) {
  const std::string prefix = run_label.empty() ? "" : csv_field(run_label) + ",";
  if (header)
    out << (run_label.empty() ? "" : "run,") << "iteration,time,displacement,lower_bound,upper_bound,gamma,gamma_effective,"
         "max_displacement,violating,unstabilisable,clamped,zero_length_springs,"
         "safe_bound,unguaranteed,compressed_springs\n";
  for (const StepStats& s : trace)
    out << prefix << s.iteration << ',' << format_number(s.time) << ','
        << format_number(s.watched_displacement) << ',' << format_number(s.watched_lower) << ','
        << format_number(s.watched_upper) << ',' << format_number(s.watched_gamma) << ','
        << format_number(s.watched_gamma_eff) << ',' << format_number(s.max_displacement) << ','
        << s.violating << ',' << s.unstabilisable << ',' << s.clamped << ','
        << s.zero_length_springs << ',' << format_number(s.watched_safe) << ','
        << s.unguaranteed << ',' << s.compressed_springs << '\n';
}

std::string result_json(const std::string& scene, const Params& p, const StopRules& rules,
                        int watched, const RunResult& r) {
  std::ostringstream os;
  os << "{\"scene\":" << json_string(scene) << ",\"m\":" << json_number(p.m)
     << ",\"kappa\":" << json_number(p.kappa) << ",\"gamma\":" << json_number(p.gamma)
     << ",\"dt\":" << json_number(p.dt) << ",\"policy\":" << json_string(to_string(p.policy))
     << ",\"factor\":" << json_number(p.factor)
     << ",\"integrator\":" << json_string(to_string(p.integrator))
     << ",\"max_iterations\":" << rules.max_iterations << ",\"watched\":" << watched
     << ",\"outcome\":" << json_string(to_string(r.outcome)) << ",\"iterations\":" << r.iterations
     << ",\"time\":" << json_number(r.time)
     << ",\"max_displacement\":" << json_number(r.max_displacement)
     << ",\"violations\":" << r.violations << ",\"unstabilisable\":" << r.unstabilisable
     << ",\"clamped\":" << r.clamped << ",\"zero_length_springs\":" << r.zero_length_springs
     << ",\"unguaranteed\":" << r.unguaranteed
     << ",\"compressed_springs\":" << r.compressed_springs << "}";
  return os.str();
}

}  // namespace dampbound
