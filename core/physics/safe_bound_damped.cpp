#include "core/physics/safe_bound_damped.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "core/physics/detail/spring_block.hpp"

namespace dampbound {

namespace {

/// Spring k's blocks at x: K's B and C''s E = beta B + kd d d^T (both 3 x 3); false when
/// the spring has no direction (SPEC 1).
bool spring_blocks(const Model& model, const std::vector<Vec3>& x, size_t k, Eigen::Matrix3d& B,
                   Eigen::Matrix3d& E) {
  const Spring& s = model.spec().springs[k];
  const SpringGeometry g = spring_geometry(x[static_cast<size_t>(s.i)].data(),
                                                   x[static_cast<size_t>(s.j)].data(), s.rest_length);
  if (!(g.length > 0)) return false;
  const Vec3 d(g.d[0], g.d[1], g.d[2]);
  const double ratio = g.ratio, tension = g.tension;
  const Eigen::Matrix3d P = d * d.transpose();
  B = model.spring_kappa[k] * (ratio * P + tension * Eigen::Matrix3d::Identity());
  E = model.rayleigh_stiffness * B + model.spring_kd[k] * P;
  return true;
}

/// sqrt(P^2 + 16 Q) without forming P^2, which overflows for a rate above ~1e154 (an
/// extreme alpha or kd) and would send the row's root to 0 and its limit to +inf; NaN where
/// P^2 + 16 Q < 0 (no real root).
double discriminant_root(double P, double Q) {
  const double a = 4 * std::sqrt(std::abs(Q));
  if (Q >= 0) return std::hypot(P, a);
  const double p = std::abs(P);
  if (!(p >= a)) return std::numeric_limits<double>::quiet_NaN();
  return std::sqrt(p - a) * std::sqrt(p + a);
}

}  // namespace

namespace {

/// Spring k's entries in the rows of one end, towards a free other end of masses product
/// `mm` (m_i m_j): entry(r, a, c) for the block's nine entries, row by row, a and c its K and
/// C' blocks weighted by 1/sqrt(m_i m_j), negated. The same at both ends (B and E are
/// symmetric, entry by entry, and so is m_i m_j).
template <class OnEntry>
void neighbour_entries(const Eigen::Matrix3d& B, const Eigen::Matrix3d& E, double mm,
                       OnEntry entry) {
  const double w = 1.0 / std::sqrt(mm);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) entry(r, -B(r, c) * w, -E(r, c) * w);
}

/// SPEC 10's row-sum term of one entry (a, c) at dt: |2 dt c + dt^2 a|.
inline double entry_term(double dt, double a, double c) { return std::abs(2 * dt * c + dt * dt * a); }

/// Node i's own block after its springs' (Ka = K_ii, Kc = C'_ii less alpha M): entry(r, a, c)
/// for the entries off the diagonal, then diag(r, a_rr, c'_rr), row by row.
template <class OnEntry, class OnDiag>
void own_block(const Model& model, size_t i, const Eigen::Matrix3d& Ka, const Eigen::Matrix3d& Kc,
               OnEntry entry, OnDiag diag) {
  const double m = model.mass[i];
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c)
      if (c != r) entry(r, Ka(r, c) / m, Kc(r, c) / m);
    diag(r, Ka(r, r) / m, model.rayleigh_mass + Kc(r, r) / m);
  }
}

/// The node's part of its own block before any spring: the anchor's stiffness and damping.
void anchor_blocks(const Model& model, size_t i, Eigen::Matrix3d& Ka, Eigen::Matrix3d& Kc) {
  Ka = model.anchor_kappa[i] * Eigen::Matrix3d::Identity();
  Kc = (model.rayleigh_stiffness * model.anchor_kappa[i] + model.anchor_kd[i]) *
       Eigen::Matrix3d::Identity();
}

/// Node i's three rows of A = M^-1 K and C' = M^-1 C (SPEC 10), the one walk that both the
/// stored rows and damped_safe_gammas() follow: entry(r, a, c) for each entry off the
/// diagonal, the free neighbours' blocks in incidence order (ascending spring index) and then
/// the node's own block, and diag(r, a_rr, c'_rr) after row r's last entry. Nothing for a
/// fixed node.
template <class OnEntry, class OnDiag>
void node_rows(const Model& model, const std::vector<Vec3>& x, size_t i, OnEntry entry,
               OnDiag diag) {
  if (model.spec().fixed[i]) return;
  const double m = model.mass[i];
  Eigen::Matrix3d B, E, Ka, Kc;
  anchor_blocks(model, i, Ka, Kc);
  for (int e = model.incident_offset[i]; e < model.incident_offset[i + 1]; ++e) {
    const int code = model.incident[static_cast<size_t>(e)];
    const size_t k = static_cast<size_t>(code >= 0 ? code : ~code);
    if (!spring_blocks(model, x, k, B, E)) continue;
    Ka += B;
    Kc += E;
    const Spring& s = model.spec().springs[k];
    const size_t j = static_cast<size_t>(code >= 0 ? s.j : s.i);
    if (model.spec().fixed[j]) continue;
    neighbour_entries(B, E, m * model.mass[j], entry);
  }
  own_block(model, i, Ka, Kc, entry, diag);
}

}  // namespace

DampedSafeRows::DampedSafeRows(const Model& model, const std::vector<Vec3>& x)
    : mass_(model.mass) {
  const size_t n = model.spec().rest.size();
  diag_a_.assign(3 * n, 0);
  diag_c_.assign(3 * n, 0);
  offset_.assign(3 * n + 1, 0);
  // Node blocks (K_ii, C'_ii) and, per row, the neighbours' entries, node by node.
  std::vector<Entry> row_entries[3];
  for (size_t i = 0; i < n; ++i) {
    for (auto& r : row_entries) r.clear();
    node_rows(
        model, x, i, [&](int r, double a, double c) { row_entries[r].push_back({a, c}); },
        [&](int r, double diag_a, double diag_c) {
          diag_a_[3 * i + r] = diag_a;
          diag_c_[3 * i + r] = diag_c;
        });
    for (int r = 0; r < 3; ++r) {
      entries_.insert(entries_.end(), row_entries[r].begin(), row_entries[r].end());
      offset_[3 * i + r + 1] = static_cast<int>(entries_.size());
    }
  }
}

DampedSafeRows::DampedSafeRows(const Eigen::SparseMatrix<double>& A,
                               const Eigen::SparseMatrix<double>& Cp,
                               const std::vector<double>& mass)
    : mass_(mass) {
  const Eigen::Index rows = A.rows();
  diag_a_.assign(size_t(rows), 0);
  diag_c_.assign(size_t(rows), 0);
  offset_.assign(size_t(rows) + 1, 0);
  // Row r of a symmetric matrix is its column r: merge A's and Cp's, sorted by index.
  for (Eigen::Index r = 0; r < rows; ++r) {
    Eigen::SparseMatrix<double>::InnerIterator a(A, r), c(Cp, r);
    while (a || c) {
      const Eigen::Index s = !c || (a && a.row() < c.row()) ? a.row() : c.row();
      double va = 0, vc = 0;
      if (a && a.row() == s) va = a.value(), ++a;
      if (c && c.row() == s) vc = c.value(), ++c;
      if (s == r) {
        diag_a_[size_t(r)] = va;
        diag_c_[size_t(r)] = vc;
      } else {
        entries_.push_back({va, vc});
      }
    }
    offset_[size_t(r) + 1] = static_cast<int>(entries_.size());
  }
}

double DampedSafeRows::gamma_safe(int node, double dt) const {
  const size_t i = static_cast<size_t>(node);
  double margin = std::numeric_limits<double>::infinity();
  for (size_t r = 3 * i; r < 3 * i + 3; ++r) {
    double off = 0;
    for (int e = offset_[r]; e < offset_[r + 1]; ++e) {
      const Entry& q = entries_[static_cast<size_t>(e)];
      off += entry_term(dt, q.a, q.c);
    }
    margin = std::min(margin, 4 - 2 * dt * diag_c_[r] - dt * dt * diag_a_[r] - off);
  }
  return mass_[i] / (2 * dt) * margin;
}

double DampedSafeRows::dt_safe(int node, double gamma) const {
  const size_t i = static_cast<size_t>(node);
  const double rate = gamma / mass_[i];
  double best = std::numeric_limits<double>::infinity();
  for (size_t r = 3 * i; r < 3 * i + 3; ++r) {
    // margin(dt) = 4 - dt (P + Q dt) on each interval between the dt where an entry
    // 2 dt c + dt^2 a changes sign (dt = -2c/a > 0); first root of Q dt^2 + P dt = 4.
    std::vector<double> cuts{0.0};
    for (int e = offset_[r]; e < offset_[r + 1]; ++e) {
      const Entry& q = entries_[static_cast<size_t>(e)];
      if (q.a != 0 && -2 * q.c / q.a > 0) cuts.push_back(-2 * q.c / q.a);
    }
    std::sort(cuts.begin(), cuts.end());
    cuts.push_back(std::numeric_limits<double>::infinity());
    for (size_t p = 0; p + 1 < cuts.size() && cuts[p] < best; ++p) {
      const double lo = cuts[p], hi = cuts[p + 1];
      const double mid = std::isinf(hi) ? (lo > 0 ? 2 * lo : 1.0) : 0.5 * (lo + hi);
      double P = 2 * (rate + diag_c_[r]), Q = diag_a_[r];
      for (int e = offset_[r]; e < offset_[r + 1]; ++e) {
        const Entry& q = entries_[static_cast<size_t>(e)];
        const double sign = (2 * q.c + mid * q.a) < 0 ? -1.0 : 1.0;
        P += sign * 2 * q.c;
        Q += sign * q.a;
      }
      // smallest root of Q t^2 + P t - 4 = 0 in [lo, hi]
      double root = std::numeric_limits<double>::infinity();
      if (Q == 0) {
        if (P > 0) root = 4 / P;
      } else {
        const double s = discriminant_root(P, Q);
        if (!std::isnan(s)) {
          // Roots without cancellation: q = -(P + sign(P) s) / 2, roots q / Q and -4 / q
          // (their product is -4 / Q). (-P + s) / (2Q) rounds to 0 when 16 Q is below P^2's
          // last bit, and a root dropped there would leave the row's limit at +inf.
          const double q = -(0.5 * P + (P < 0 ? -0.5 * s : 0.5 * s));
          const double r1 = q / Q, r2 = -4 / q;  // q != 0: Q != 0 and disc >= 0
          for (double t : {std::min(r1, r2), std::max(r1, r2)})
            if (t >= lo && t <= hi && t > 0) {
              root = t;
              break;
            }
        }
      }
      if (root <= hi) {
        best = std::min(best, root);
        break;
      }
    }
  }
  return best;
}

namespace {

/// One node's sums in damped_safe_gammas' pass: its own block's K and C' parts so far and the
/// absolute sums of its rows' entries towards its neighbours.
struct NodeSums {
  Eigen::Matrix3d Ka, Kc;
  double off[3];
};

}  // namespace

void damped_safe_gammas(const Model& model, const std::vector<Vec3>& x, double dt,
                        std::vector<double>& gamma_safe, NodeThreads* threads) {
  const size_t n = model.spec().rest.size();
  gamma_safe.assign(n, std::numeric_limits<double>::infinity());
  const std::vector<std::uint8_t>& fixed = model.spec().fixed;
  const std::vector<Spring>& springs = model.spec().springs;
  // DampedSafeRows::gamma_safe's sums, in node_rows' order, without storing the rows: each
  // spring's blocks once for both of its ends (the springs in list order are each node's
  // incidence order), the nodes' sums in a buffer. Each node's sums are its own: the nodes
  // split across threads with the same bits (a spring between two threads' nodes is formed
  // by both).
  const auto nodes = [&](int, size_t begin, size_t end) {
    thread_local std::vector<NodeSums> sums;
    sums.resize(end - begin);
    for (size_t i = begin; i < end; ++i) {
      NodeSums& q = sums[i - begin];
      anchor_blocks(model, i, q.Ka, q.Kc);
      q.off[0] = q.off[1] = q.off[2] = 0;
    }
    Eigen::Matrix3d B, E;
    for (size_t k = 0; k < springs.size(); ++k) {
      const size_t i = static_cast<size_t>(springs[k].i), j = static_cast<size_t>(springs[k].j);
      const bool at_i = i >= begin && i < end && !fixed[i];
      const bool at_j = j != i && j >= begin && j < end && !fixed[j];
      if (!(at_i || at_j) || !spring_blocks(model, x, k, B, E)) continue;
      // The entries' terms, once for both ends (only where both are free).
      double term[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
      const bool both = !fixed[i] && !fixed[j];
      if (both) {
        int e = 0;
        neighbour_entries(B, E, model.mass[i] * model.mass[j],
                          [&](int, double ea, double ec) { term[e++] = entry_term(dt, ea, ec); });
      }
      for (const auto& [a, here] : {std::pair{i, at_i}, std::pair{j, at_j}}) {
        if (!here) continue;
        NodeSums& q = sums[a - begin];
        q.Ka += B;
        q.Kc += E;
        if (!both) continue;
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) q.off[r] += term[3 * r + c];
      }
    }
    for (size_t i = begin; i < end; ++i) {
      if (fixed[i]) continue;
      NodeSums& q = sums[i - begin];
      double margin = std::numeric_limits<double>::infinity();
      own_block(
          model, i, q.Ka, q.Kc,
          [&](int r, double a, double c) { q.off[r] += entry_term(dt, a, c); },
          [&](int r, double diag_a, double diag_c) {
            margin = std::min(margin, 4 - 2 * dt * diag_c - dt * dt * diag_a - q.off[r]);
          });
      gamma_safe[i] = model.mass[i] / (2 * dt) * margin;
    }
  };
  if (threads)
    threads->run(n, nodes);
  else
    nodes(0, 0, n);
}

}  // namespace dampbound
