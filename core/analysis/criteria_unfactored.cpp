#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
#include "core/analysis/criteria_unfactored.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "core/io/format.hpp"
#include "core/physics/detail/numbers.hpp"

namespace dampbound {
namespace {
}  // namespace

std::string over_budget_test(const ExactStability& exact) {
  return "not computed: " + exact.over_budget_reason();
}

namespace {

/// An exact row over the budget (`c`: its name and reason so far; `without`: the proofs'
/// preamble): the user's `what` against the value from which (or up to which, `below`)
/// instability is proved at the other parameter `at` (inf: none is; inf and `below`: every
/// value is; NaN: no such threshold, RK4), and against the range [stable_lo, stable_hi]
/// proved stable (none when NaN).
CriterionResult threshold_row(CriterionResult c, const std::string& without,
                              const std::string& what, double user, double from,
                              const std::string& at, bool below, double stable_lo,
                              double stable_hi) {
  const bool has_stable = stable_lo <= stable_hi;  // false for NaN
  bool unstable = false, told = true;  // told: the proof names a threshold
  std::string proof;
  if (below && from == kInf) {  // gamma changes nothing (no damping rate anywhere)
    unstable = true;
    told = false;
    proof = "every " + what + " is unstable at this " + at;
  } else if (std::isnan(from)) {  // RK4: its instability proof holds at the user's point only
    told = false;
  } else if (std::isinf(from)) {  // nothing is proved in this direction
    told = false;
    proof = "no " + what + " is proved unstable at this " + at;
  } else {
    unstable = below ? user <= from : user >= from;
    proof = "every " + what + (below ? " <= " : " >= ") + format_human(from) +
            " is unstable at this " + at;
  }
  const bool stable = !unstable && has_stable && stable_lo <= user && user <= stable_hi;
  if (has_stable) {
    const std::string range =
        stable_lo <= 0 ? (std::isinf(stable_hi) ? ">= 0" : "<= " + format_human(stable_hi))
        : std::isinf(stable_hi)
            ? ">= " + format_human(stable_lo)
            : "in [" + format_human(stable_lo) + ", " + format_human(stable_hi) + "]";
    proof += (proof.empty() ? "" : ", ") + ("every " + what + " " + range + " is stable");
  }
  c.verdict = unstable ? CriterionVerdict::beyond
                       : stable ? CriterionVerdict::within : CriterionVerdict::not_applicable;
  c.test += without + proof;
  if (told || has_stable)
    c.test += "; " + what + " = " + format_human(user) +
              (unstable ? " is" : stable ? " is stable" : " is not proved either way");
  return c;
}

}  // namespace

/// The exact rows over the factorisation budget: nothing exact, but what plain Lanczos,
/// Gershgorin and the node-block splitting prove without a factorisation
/// (ExactStability::Unfactored): a bracket of lambda_max; for the paper's step a proof of
/// instability where its Rayleigh quotient reaches the index's 4; for forward Euler, Verlet
/// and RK4 at uniform rates the per-mode proofs (either way; RK4's at the user's gamma and dt
/// only); for the paper's step with K >= 0 the lower of Gershgorin on the index matrix (SPEC
/// 9's safe bound) and the splitting on the stable side. Where nothing is proved the row has
/// no verdict.
std::vector<CriterionResult> unfactored_criteria(const ExactStability& e, const Params& params) {
  const ExactStability::Unfactored& b = e.unfactored;
  const std::string integ = to_string(e.integrator);
  const std::string why = over_budget_test(e);
  const bool tried = !std::isnan(b.lambda_max_lo);
  const std::string without =
      "; without a factorisation (Lanczos, " + std::to_string(b.lanczos_steps) + " steps" +
      (b.patch_nodes > 0 ? "; a patch of " + std::to_string(b.patch_nodes) +
                               " nodes around the index's top"
                         : std::string()) +
      "): ";
  std::vector<CriterionResult> out;
  auto row = [&](const std::string& name) {
    CriterionResult c;
    c.name = name;
    c.source = "exact";
    c.formula = "not computed";
    c.value = std::numeric_limits<double>::quiet_NaN();
    c.verdict = CriterionVerdict::not_applicable;
    c.test = why;
    return c;
  };
  CriterionResult lm = row("exact lambda_max of M^-1 K");
  if (tried)
    lm.test +=
        without + "lambda_max in [" + format_human(b.lambda_max_lo) + ", " +
        format_human(b.lambda_max_hi) + "] (" +
        (b.lambda_patch_nodes > 0
             ? "a patch of " + std::to_string(b.lambda_patch_nodes) +
                   " nodes around A's top, each node outside it alone; Gershgorin's: " +
                   format_human(b.gershgorin)
         : b.lambda_max_hi < b.gershgorin
             ? "a Rayleigh quotient, the node-block splitting's bound; Gershgorin's: " +
                   format_human(b.gershgorin)
             : std::string("a Rayleigh quotient, Gershgorin's bound")) +
        ")";
  out.push_back(lm);
  if (b.unconditional) {  // implicit Euler, K >= 0: every row but lambda_max is exact
    auto within = [&](const std::string& name, double value, const std::string& unit,
                      const std::string& test) {
      CriterionResult c = row(name);
      c.value = value;
      c.unit = unit;
      c.verdict = CriterionVerdict::within;
      c.test += test;
      return c;
    };
    const double inf = std::numeric_limits<double>::infinity();
    out.push_back(within("exact spectral radius (" + integ + ")",
                         std::numeric_limits<double>::quiet_NaN(), "",
                         "; stable for every dt and gamma: K is positive semidefinite (the safe "
                         "bound's floor, no spring compressed), which needs no factorisation"));
    out.push_back(within("exact gamma interval (" + integ + ")", inf, "mass unit/s",
                         "; gamma = " + format_human(params.gamma) + " in [0, inf)"));
    out.push_back(within("exact dt limit (" + integ + ")", inf, "s",
                         "; dt = " + format_human(params.dt) + " <= dt_max = inf"));
    return out;
  }
  const bool index = tried && !std::isnan(b.index_at_least);
  const bool modes = tried && !std::isnan(b.mode_unstable_from);  // forward Euler, Verlet, RK4
  CriterionResult rho = row("exact spectral radius (" + integ + ")");
  if (index) {
    const bool unstable = b.index_at_least >= 4;
    const bool stable = !unstable && b.index_at_most < 4;  // false for NaN
    rho.verdict = unstable ? CriterionVerdict::beyond
                  : stable ? CriterionVerdict::within
                           : CriterionVerdict::not_applicable;
    rho.test += without + "index lambda_max(dt^2 A + 2 dt C) >= " +
                format_human(b.index_at_least) +
                (unstable ? " >= 4: unstable (proved)" : " (< 4 proves nothing)");
    if (!unstable && !std::isnan(b.index_at_most))
      rho.test +=
          "; <= " + format_human(b.index_at_most) +
          (b.index_at_most == b.index_patch
               ? " (no spring compressed: K >= 0; the patch, each node outside it alone; "
                 "Gershgorin on its rows, the safe bound: " +
                     format_human(b.index_gershgorin) + ")"
           : b.index_at_most < b.index_gershgorin
               ? " (no spring compressed: K >= 0; the node-block splitting; Gershgorin on "
                 "its rows, the safe bound: " +
                     format_human(b.index_gershgorin) + ")"
               : " (no spring compressed: K >= 0; Gershgorin on its rows, the safe bound)") +
          (stable ? " < 4: stable (proved)" : ", which proves nothing");
  } else if (modes) {
    const bool unstable = b.lambda_max_lo >= b.mode_unstable_from;
    const bool stable_side = !std::isnan(b.stable_lambda_hi), stable = stable_side && e.stable;
    rho.verdict = unstable ? CriterionVerdict::beyond
                           : stable ? CriterionVerdict::within : CriterionVerdict::not_applicable;
    rho.test += without + "every mode with lambda >= " + format_human(b.mode_unstable_from) +
                " is unstable at this gamma and dt; lambda_max >= " +
                format_human(b.lambda_max_lo) +
                (unstable ? ": unstable (proved)" : " proves nothing");
    if (!unstable && stable_side)
      rho.test += "; every mode lies in [0, " + format_human(b.stable_lambda_hi) +
                  "] (no spring compressed: K >= 0; " +
                  (b.lambda_max_hi < b.gershgorin ? "the node-block splitting's bound)"
                                                  : "Gershgorin's bound)") +
                  (stable ? " and each is stable at this gamma and dt: stable (proved)"
                          : ", which proves no stability at this gamma and dt");
  }
  out.push_back(rho);
  auto threshold = [&](const std::string& name, const std::string& what, double user,
                       double from, const std::string& at, bool below,
                       double stable_lo = kNaN, double stable_hi = kNaN) {
    if (!index && !modes) return row(name);
    return threshold_row(row(name), without, what, user, from, at, below, stable_lo, stable_hi);
  };
  // RK4: its instability proof is for the user's gamma and dt; the rows below add the
  // gammas and dts proved stable around them.
  auto at_point = [&](const std::string& name) {
    CriterionResult c = row(name);
    c.verdict = rho.verdict;
    c.test += without + (rho.verdict == CriterionVerdict::beyond
                             ? "unstable at this gamma and dt (proved: the spectral radius row)"
                         : rho.verdict == CriterionVerdict::within
                             ? "stable at this gamma and dt (proved: the spectral radius row)"
                             : "not proved either way at this gamma and dt");
    return c;
  };
  const std::string gamma_row = "exact gamma interval (" + integ + ")",
                    dt_row = "exact dt limit (" + integ + ")";
  if (modes && std::isnan(b.dt_unstable_from)) {  // RK4: thresholds on the stable side only
    const bool open = rho.verdict != CriterionVerdict::beyond;
    out.push_back(open && b.gamma_stable_lo <= b.gamma_stable_hi
                      ? threshold(gamma_row, "gamma", params.gamma, kNaN, "dt", true,
                                  b.gamma_stable_lo, b.gamma_stable_hi)
                      : at_point(gamma_row));
    out.push_back(open && b.dt_stable_up_to > 0 ? threshold(dt_row, "dt", params.dt, kNaN, "gamma",
                                                            false, 0.0, b.dt_stable_up_to)
                                                : at_point(dt_row));
    return out;
  }
  out.push_back(modes ? threshold(gamma_row, "gamma", params.gamma, b.gamma_unstable_below, "dt",
                                  true, b.gamma_stable_lo, b.gamma_stable_hi)
                      : threshold(gamma_row, "gamma", params.gamma, b.gamma_unstable_from, "dt",
                                  false, b.gamma_stable_lo, b.gamma_stable_hi));
  out.push_back(threshold(dt_row, "dt", params.dt, b.dt_unstable_from, "gamma", false,
                          std::isnan(b.dt_stable_up_to) ? kNaN : 0.0, b.dt_stable_up_to));
  return out;
}

}  // namespace dampbound
