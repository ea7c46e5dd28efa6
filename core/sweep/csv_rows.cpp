#include "core/sweep/csv_rows.hpp"

#include <cmath>
#include <cstdlib>
#include <map>
#include <vector>

#include "core/io/format.hpp"
#include "core/sweep/summary.hpp"
#include "dampbound/physics/bounds.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound {

namespace {

std::vector<std::string> fields_of(const std::string& line) {
  std::vector<std::string> out;
  size_t start = 0;
  for (;;) {
    const size_t p = line.find(',', start);
    out.push_back(line.substr(start, p == std::string::npos ? std::string::npos : p - start));
    if (p == std::string::npos) return out;
    start = p + 1;
  }
}

std::vector<double> values(const Axis& a) {
  std::vector<double> v;
  for (const Decimal& d : a.values) v.push_back(d.value());
  return v;
}

}  // namespace

SweepGrid grid_of_header(const SweepHeader& h, const std::string& path) {
  auto axis = [&](const char* key, const char* flag, AxisDomain domain) {
    const auto text = definition_value(h.definition, key);
    if (!text) throw InputError(path + ": the definition names no " + key + " axis");
    try {
      return parse_axis(flag, *text, domain);
    } catch (const InputError& e) {
      throw InputError(path + ": the definition's " + key + " axis: " + e.what());
    }
  };
  SweepSpec s;
  s.m = axis("m", "--m", AxisDomain::positive);
  s.kappa = axis("kappa", "--kappa", AxisDomain::positive);
  const bool zeta = definition_value(h.definition, "zeta").has_value();
  s.gamma_mode = zeta ? GammaMode::zeta : GammaMode::absolute;
  s.gamma = zeta ? axis("zeta", "--zeta", AxisDomain::non_negative)
                 : axis("gamma", "--gamma", AxisDomain::non_negative);
  s.dt = axis("dt", "--dt", AxisDomain::positive);
  s.factor = axis("factor", "--factor", AxisDomain::non_negative);
  if (h.damping) {
    s.kd = axis("kd", "--kd", AxisDomain::non_negative);
    s.rayleigh_mass = axis("rayleigh-mass", "--rayleigh-mass", AxisDomain::non_negative);
    s.rayleigh_stiffness =
        axis("rayleigh-stiffness", "--rayleigh-stiffness", AxisDomain::non_negative);
  }
  if (h.policy) s.policy = *h.policy;
  return SweepGrid(std::move(s));
}

void check_sweep_rows(const SweepTable& t, const std::string& path) {
  const SweepHeader& h = t.header;
  const SweepGrid grid = grid_of_header(h, path);
  if (grid.trials() != h.trials)
    throw InputError(path + ": the header says " + std::to_string(h.trials) +
                     " trials, its definition's axes make " + std::to_string(grid.trials()));
  const SweepSpec& s = grid.spec();
  const auto mv = values(s.m), kv = values(s.kappa), gv = values(s.gamma), dv = values(s.dt),
             fv = values(s.factor), kdv = values(s.kd), av = values(s.rayleigh_mass),
             bv = values(s.rayleigh_stiffness);
  // The band of the definition (SPEC 5, 8).
  auto rule_number = [&](const char* key, double fallback) {
    const auto text = definition_value(h.definition, key);
    return text ? c_strtod(text->c_str(), nullptr) : fallback;
  };
  const StopRules defaults;
  const double reference = rule_number("reference", defaults.reference);
  const double band = rule_number("restore-fraction", defaults.restore_fraction) * reference;
  const double diverge = rule_number("diverge-factor", defaults.diverge_factor) * reference;
  const double max_iter = rule_number("max-iter", defaults.max_iterations);
  const size_t extra = h.damping ? 3 : 0;
  struct ClassSeen {
    std::string result;  ///< the fields from outcome on
    std::uint64_t first = 0;
  };
  std::map<std::uint64_t, ClassSeen> classes;
  for (size_t r = 0; r < t.rows.size() && r < t.lines.size(); ++r) {
    const SweepRow& row = t.rows[r];
    const std::vector<std::string> f = fields_of(t.lines[r]);
    const std::string at = path + ": trial " + std::to_string(row.trial) + ": ";
    if (row.trial >= grid.trials()) throw InputError(at + "outside the sweep");
    const SweepGrid::Index ix = grid.index(row.trial);
    auto same = [&](const char* column, double got, double want) {
      if (!(got == want))
        throw InputError(at + column + " is " + format_number(got) + ", the sweep's grid has " +
                         format_number(want) + " there (a row edited under its header?)");
    };
    same("m", row.m, mv[ix.m]);
    same("kappa", row.kappa, kv[ix.kappa]);
    const double lo = lower_bound(row.m, row.kappa);
    if (s.gamma_mode == GammaMode::zeta) {
      same("zeta", row.zeta, gv[ix.gamma]);
      same("gamma", row.gamma, gv[ix.gamma] * lo);
    } else {
      same("gamma", row.gamma, gv[ix.gamma]);
      same("zeta", row.zeta, gv[ix.gamma] / lo);
    }
    same("dt", row.dt, dv[ix.dt]);
    same("factor", row.factor, fv[ix.factor]);
    if (h.damping) {
      same("kd", row.kd, kdv.empty() ? 0.0 : kdv[ix.kd]);
      same("rayleigh_mass", row.rayleigh_mass, av.empty() ? 0.0 : av[ix.rayleigh_mass]);
      same("rayleigh_stiffness", row.rayleigh_stiffness,
           bv.empty() ? 0.0 : bv[ix.rayleigh_stiffness]);
    }
    if (f[6] != to_string(s.policy))
      throw InputError(at + "policy '" + printable(f[6]) + "', the sweep's is " +
                       to_string(s.policy));
    // One result per class, run at its first trial (ran = 1 there only).
    char* end = nullptr;
    const std::uint64_t cls = std::strtoull(f[8 + extra].c_str(), &end, 10);
    if (f[8 + extra].empty() || *end || cls >= h.classes)
      throw InputError(at + "class '" + printable(f[8 + extra]) + "' is not one of the " +
                       std::to_string(h.classes) + " classes");
    const std::string& ran = f[9 + extra];
    std::string result;
    for (size_t k = 10 + extra; k < f.size(); ++k) result += f[k] + ',';
    const auto [seen, fresh] = classes.emplace(cls, ClassSeen{result, row.trial});
    if (ran != (fresh ? "1" : "0"))
      throw InputError(at + "ran = " + printable(ran) + ", but " +
                       (fresh ? "it is the first trial of class " + std::to_string(cls)
                              : "class " + std::to_string(cls) + " ran at trial " +
                                    std::to_string(seen->second.first)));
    if (!fresh && seen->second.result != result)
      throw InputError(at + "its result differs from trial " +
                       std::to_string(seen->second.first) + "'s, of the same class " +
                       std::to_string(cls));
    // The outcome agrees with the band and the limit.
    const double x = row.max_displacement;
    const bool ok = [&] {
      switch (row.outcome) {
        case Outcome::restored:
          return x < band && row.iterations <= max_iter;
        case Outcome::settled:  // at the limit, or earlier where SPEC 8's proof stopped it
          return x < band && row.iterations <= max_iter && row.settled_at > 0 &&
                 row.settled_at <= row.iterations;
        case Outcome::diverged:  // a non-finite state diverges whatever its displacement
          return row.iterations <= max_iter;
        case Outcome::not_restored:
        case Outcome::not_settled:
          return row.iterations == max_iter && !(x > diverge);
        case Outcome::running:
          return false;
      }
      return false;
    }();
    if (!ok)
      throw InputError(at + "outcome " + to_string(row.outcome) + " at iteration " +
                       std::to_string(row.iterations) + " with max |x-X| " + format_number(x) +
                       " cm contradicts the band (" + format_number(band) + " cm, diverged above " +
                       format_number(diverge) + " cm, limit " + format_number(max_iter) + ")");
  }
}

}  // namespace dampbound
