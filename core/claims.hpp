#pragma once
// The paper's claims, each beside what dampbound measured and whether it holds (for
// `dampbound reproduce`). Claims are judged from measured data only; nothing is tuned.
#include <iosfwd>
#include <string>
#include <vector>

#include "core/figures.hpp"
#include "core/sweep_summary.hpp"

namespace dampbound {

enum class ClaimVerdict { holds, does_not_hold, partly };
const char* to_string(ClaimVerdict v);

struct Claim {
  std::string source;    ///< where the paper says it ("sec. 4, Fig. 1")
  std::string paper;     ///< the claim in the paper's words
  std::string measured;  ///< what dampbound measured, with numbers
  ClaimVerdict verdict = ClaimVerdict::does_not_hold;
};

/// What a run does after its restore: stepped on to `until` iterations.
struct AfterRestore {
  bool restored = false;
  int restored_at = 0;
  int until = 0;
  bool diverged = false;
  int diverged_at = 0;
  double max_after = 0;  ///< largest max displacement (cm) after the restore
  double threshold = 0;  ///< the restore threshold (cm)
};

/// Runs the scene with the run's parameters to its outcome, then (when restored) on to
/// `until` iterations, recording whether it stays within the threshold.
AfterRestore run_after_restore(const SceneSpec& scene, const FigureRun& run, int until);

/// Fig. 1: below the lower bound the mesh keeps oscillating; at it, it settles after 34.
std::vector<Claim> fig1_claims(const FigureData& fig1);

/// Fig. 2: at the upper bound stable within 652 iterations and after; 5% above, unstable.
std::vector<Claim> fig2_claims(const FigureData& fig2, const AfterRestore& at_bound);

/// A sweep's prediction checks (core/sweep_summary.hpp) as claims of the paper's sec. 4:
/// holds when it held in every trial, partly when in some, does not hold when in none.
/// Checks whose text does not mention the paper (dampbound's own, e.g. SPEC 7) are skipped.
std::vector<Claim> sweep_claims(const std::vector<PredictionCheck>& checks,
                                const std::string& source, const std::string& grid);

/// Markdown table of the claims.
void write_claims_table(std::ostream& out, const std::vector<Claim>& claims);

}  // namespace dampbound
