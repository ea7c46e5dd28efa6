#include "core/analysis/detail/symmetric_product.hpp"

namespace dampbound::detail {

void symmetric_product(const SparseMatrix& A, const Eigen::VectorXd& v, double b,
                       const Eigen::VectorXd& p, Eigen::VectorXd& w, NodeThreads& threads) {
  w.resize(A.rows());
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  const double* value = A.valuePtr();
  const int* count = A.innerNonZeroPtr();  // null when compressed (assembled matrices are)
  threads.run(static_cast<size_t>(A.rows()), [&](int, size_t begin, size_t end) {
    for (size_t r = begin; r < end; ++r) {
      const int first = outer[r];
      const int last = count ? first + count[r] : outer[r + 1];
      double sum = 0;
      for (int k = first; k < last; ++k) sum += value[k] * v[inner[k]];
      w[static_cast<Eigen::Index>(r)] = sum - b * p[static_cast<Eigen::Index>(r)];
    }
  });
}

}  // namespace dampbound::detail
