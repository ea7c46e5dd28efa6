#pragma once
// One model's certified spectrum and pattern analysis, shared by the exact analyses that ask
// about it in turn (ExactOptions::shared): suggest's analyses at the scene's gamma and at
// gamma_min, the substep count, the tuner's Criteria tab from one change of gamma, dt or the
// damping to the next. The spectrum of A = M^-1/2 K M^-1/2 depends on the masses, the springs
// and the state alone, so a call whose A is the last one's, entry for entry (and whose floor
// and factorisation budget are), takes the spectrum as it was certified; the limit searches go
// on with the factors the last call left (one pattern analysis). The results are the bits of
// a call that computes everything anew: the spectrum is the same function of the same
// matrix, and a pattern analysed again with CHOLMOD's ordering is the same analysis.
#include <memory>
#include <mutex>
#include <optional>

#include "core/analysis/linear_stability_cholesky.hpp"

namespace dampbound {

namespace detail {
class ShiftedCholesky;
}

class SharedAnalysis {
 public:
  SharedAnalysis();
  ~SharedAnalysis();
  SharedAnalysis(const SharedAnalysis&) = delete;
  SharedAnalysis& operator=(const SharedAnalysis&) = delete;

  /// The spectrum remembered for A with `floor` and `budget` (false where there is none):
  /// copied to `ends`, and the factors the last call left moved to `factors` (empty where it
  /// left none). Thread-safe: a second call at once finds no factors and makes its own.
  bool take(const SparseMatrix& A, std::optional<double> floor, double budget,
            CertifiedSpectrum& ends, std::unique_ptr<detail::ShiftedCholesky>& factors);
  /// A's spectrum as certified (after a miss), for the calls that follow; forgets the last.
  void remember(const SparseMatrix& A, std::optional<double> floor, double budget,
                const CertifiedSpectrum& ends);
  /// The factors a call leaves (their last pattern analysis and memory), for the next one.
  void keep(std::unique_ptr<detail::ShiftedCholesky> factors);
  /// How many spectra were taken as remembered.
  int hits() const;

 private:
  mutable std::mutex mutex_;
  bool have_ = false;
  SparseMatrix A_;
  std::optional<double> floor_;
  double budget_ = 0;
  CertifiedSpectrum ends_;
  std::unique_ptr<detail::ShiftedCholesky> factors_;
  int hits_ = 0;
};

}  // namespace dampbound
