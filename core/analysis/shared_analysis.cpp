#include "core/analysis/shared_analysis.hpp"

#include <algorithm>

#include "core/analysis/detail/shifted_cholesky.hpp"

namespace dampbound {

namespace {

/// A and B the same matrix: dimensions, pattern and every value's bits.
bool same_matrix(const SparseMatrix& A, const SparseMatrix& B) {
  if (A.rows() != B.rows() || A.cols() != B.cols() || A.nonZeros() != B.nonZeros() ||
      !A.isCompressed() || !B.isCompressed())
    return false;
  const auto n = static_cast<size_t>(A.nonZeros());
  return std::equal(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1,
                    B.outerIndexPtr()) &&
         std::equal(A.innerIndexPtr(), A.innerIndexPtr() + n, B.innerIndexPtr()) &&
         std::equal(A.valuePtr(), A.valuePtr() + n, B.valuePtr(),
                    [](double a, double b) { return a == b || (a != a && b != b); });
}

}  // namespace

SharedAnalysis::SharedAnalysis() = default;
SharedAnalysis::~SharedAnalysis() = default;

bool SharedAnalysis::take(const SparseMatrix& A, std::optional<double> floor, double budget,
                          CertifiedSpectrum& ends,
                          std::unique_ptr<detail::ShiftedCholesky>& factors) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!have_ || floor_ != floor || !(budget_ == budget) || !same_matrix(A, A_)) return false;
  ends = ends_;
  factors = std::move(factors_);
  ++hits_;
  return true;
}

void SharedAnalysis::remember(const SparseMatrix& A, std::optional<double> floor, double budget,
                              const CertifiedSpectrum& ends) {
  const std::lock_guard<std::mutex> lock(mutex_);
  A_ = A;
  A_.makeCompressed();
  floor_ = floor;
  budget_ = budget;
  ends_ = ends;
  have_ = true;
}

void SharedAnalysis::keep(std::unique_ptr<detail::ShiftedCholesky> factors) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (factors) factors_ = std::move(factors);
}

int SharedAnalysis::hits() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return hits_;
}

}  // namespace dampbound
