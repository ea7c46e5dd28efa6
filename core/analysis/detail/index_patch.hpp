#pragma once
// Over the factorisation budget, the paper's step: where the top of its index matrix
// S = h^2 A + 2 h gamma diag(R) is local (on a tetrahedral mesh with lumped masses the light
// corner and edge nodes' damping sets it), a patch of nodes around that top bounds the index
// from both sides without a factorisation of the whole mesh (docs/criteria.md, "A patch
// around the index's top").
//
// Above: K is the springs inside the patch P plus every other spring. Each spring's part is
// raised to its positive part (B <= B+, positive_spring_block). A spring with one node in P
// and one outside is split between its nodes, [X, -X; -X, X] <= diag((1 + a) X, (1 + 1/a) X)
// for X >= 0 and any a > 0 (2 |y^T X z| <= a y^T X y + z^T X z / a), a chosen per outside
// node as small as keeps that node's own bound under the index's lower bound; a spring with both
// nodes outside, a = 1, as in splitting_ceilings; a spring to a fixed node, X on its free node. So
// K <= K_P+ (dense on P) + blockdiag(D_j) (each node outside P alone), and S's top is at most
// the larger of the patch matrix's top and max_j (h^2 lambda_max(D_j) / m_j + 2 h gamma R_j).
// The patch's top is proved by a dense Cholesky factorisation and a bound on its rounding.
// Below: the top eigenvector of S's principal submatrix on P, zero elsewhere, is a vector
// whose Rayleigh quotient in S is at most S's top (summed with a bound on its rounding).
#include <Eigen/Core>
#include <vector>

#include "dampbound/analysis/linear_stability.hpp"

namespace dampbound::detail {

class IndexPatch {
 public:
  /// The patch at (gamma, h): the free nodes whose splitting bound on the index
  /// (h^2 ceiling_i + 2 h gamma R_i; `ceiling` from splitting_ceilings) is at least
  /// `at_least` (a proved lower bound of the index: only they can hold its top alone), grown
  /// by `layers` rings of spring neighbours. None (found() false) where that is more than
  /// kMaxNodes nodes: then the top is not local. `R` holds the rates per free dof of A (A's
  /// order: free nodes in index order, three dofs each), A is M^-1/2 K M^-1/2 at x.
  IndexPatch(const Model& model, const std::vector<Vec3>& x, const SparseMatrix& A,
             const Eigen::VectorXd& R, const std::vector<double>& ceiling, double gamma, double h,
             double at_least, int layers);

  /// The rings tried: more where the patch's two bounds still differ (exact_over_budget.cpp).
  static constexpr int kLayers[] = {3, 6, 12};
  static constexpr int kMaxNodes = 400;

  bool found() const { return !nodes_.empty(); }
  int node_count() const { return static_cast<int>(nodes_.size()); }
  /// The flops of one of its dense factorisations, (3 |P|)^3 / 3: a patch is used only where
  /// that is within the factorisation budget.
  double flops() const {
    const double n = static_cast<double>(dofs_.size());
    return n * n * n / 3;
  }

  /// Whether the index at (gamma, h) is proved below t: every node outside P below it and the
  /// patch matrix's Cholesky factorisation at a shift just under t, with its rounding bounded.
  bool proved_below(double t, double gamma, double h) const;
  /// A proved upper bound on the index at (gamma, h) (infinity if none was proved).
  double index_at_most(double gamma, double h) const;
  /// The top eigenvector of S's principal submatrix on P at (gamma, h), as a vector over A's
  /// rows (zero outside P).
  Eigen::VectorXd vector(double gamma, double h) const;
  /// u^T A u / u^T u for u zero outside P, less a bound on its rounding (A's products summed
  /// in long double over the patch's rows).
  double rayleigh_below(const Eigen::VectorXd& u) const;

 private:
  double outside(double gamma, double h) const;
  Eigen::MatrixXd index_matrix(const Eigen::MatrixXd& a, double gamma, double h) const;

  const SparseMatrix& A_;
  std::vector<int> nodes_;     ///< P's nodes, in index order
  std::vector<int> dofs_;      ///< their rows of A, three per node
  Eigen::MatrixXd upper_;      ///< M^-1/2 (K_P+ + the edge's (1 + a) X + anchors) M^-1/2 on P
  Eigen::MatrixXd principal_;  ///< A's principal submatrix on P (A's own values)
  Eigen::VectorXd rate_;       ///< R on P's rows
  std::vector<double> outside_ceiling_, outside_rate_;  ///< lambda_max(D_j) / m_j, R_j off P
  double entry_room_ = 0;          ///< upper_'s entries' rounding: 1e-12 of its largest row sum
  mutable double slack_hint_ = 0;  ///< the widest slack proved_below has needed
};

}  // namespace dampbound::detail
