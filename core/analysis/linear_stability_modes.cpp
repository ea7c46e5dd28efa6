#include "core/analysis/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
#include "core/analysis/linear_stability_modes.hpp"

#include <Eigen/Dense>
#include <Eigen/IterativeLinearSolvers>
#include <Spectra/GenEigsSolver.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <tuple>
#include <utility>
#include <vector>

namespace dampbound {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
/// "Bounded" (stable) means rho <= 1 + kMarginal: an undamped symplectic step (rho = 1
/// exactly) counts as stable, as in SPEC 7's dt < 2/sqrt(lambda_max) at gamma = 0.
constexpr double kMarginal = 1e-12;
/// The per-mode proofs' closed forms take a few roundings each: every threshold is moved
/// by this factor toward the side it proves.
constexpr double kRoundUp = 1 + 8 * std::numeric_limits<double>::epsilon();

/// One step of an integrator on y'' = -A y - C y', written once for a scalar mode and for a
/// whole mesh. `ops` gives A y, C w, (1 + h C/2)^-1 r and (I + h C + h^2 A)^-1 r.
template <class V, class Ops>
void linear_step(Integrator integrator, const Ops& ops, double h, V& y, V& w) {
  auto accel = [&](const V& yy, const V& ww) -> V { return -(ops.A(yy) + ops.C(ww)); };
  switch (integrator) {
    case Integrator::semi_implicit_euler: {  // paper eqs. 3-4: v += a h; x += v_new h
      w = w + h * accel(y, w);
      y = y + h * w;
      return;
    }
    case Integrator::forward_euler: {  // x += v_old h; v += a h
      const V a = accel(y, w);
      y = y + h * w;
      w = w + h * a;
      return;
    }
    case Integrator::verlet: {  // integrate.cpp: kick h/2, drift h, kick h/2 (damping implicit)
      const V wh = w + (h / 2) * accel(y, w);
      y = y + h * wh;
      w = ops.half_damp_solve(V(wh - (h / 2) * ops.A(y)), h);
      return;
    }
    case Integrator::rk4: {
      const V k1y = w, k1w = accel(y, w);
      const V k2y = w + (h / 2) * k1w, k2w = accel(V(y + (h / 2) * k1y), k2y);
      const V k3y = w + (h / 2) * k2w, k3w = accel(V(y + (h / 2) * k2y), k3y);
      const V k4y = w + h * k3w, k4w = accel(V(y + h * k3y), k4y);
      y = y + (h / 6) * (k1y + 2 * k2y + 2 * k3y + k4y);
      w = w + (h / 6) * (k1w + 2 * k2w + 2 * k3w + k4w);
      return;
    }
    case Integrator::implicit_euler: {  // (I + h C + h^2 A) w' = w - h A y; y' = y + h w'
      w = ops.implicit_solve(V(w - h * ops.A(y)), h);
      y = y + h * w;
      return;
    }
  }
}

struct ScalarOps {
  double lambda, c;
  double A(double y) const { return lambda * y; }
  double C(double w) const { return c * w; }
  double half_damp_solve(double r, double h) const { return r / (1 + c * h / 2); }
  double implicit_solve(double r, double h) const { return r / (1 + h * c + h * h * lambda); }
};

struct VectorOps {
  const SparseMatrix* K;
  const Eigen::VectorXd* rate;
  SparseMatrix S;  ///< I + h C + h^2 A; the solver keeps a reference to it, so it lives here
  std::unique_ptr<Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper>> cg;
  VectorOps(Integrator integrator, const SparseMatrix& Kw, const Eigen::VectorXd& c, double h)
      : K(&Kw), rate(&c) {
    if (integrator != Integrator::implicit_euler) return;
    S = (h * h) * Kw;
    for (Eigen::Index i = 0; i < S.rows(); ++i) S.coeffRef(i, i) += 1 + h * c(i);
    cg = std::make_unique<Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper>>();
    cg->setTolerance(1e-13);
    cg->compute(S);
  }
  VectorOps(const VectorOps&) = delete;
  VectorOps& operator=(const VectorOps&) = delete;
  Eigen::VectorXd A(const Eigen::VectorXd& y) const { return *K * y; }
  Eigen::VectorXd C(const Eigen::VectorXd& w) const { return rate->cwiseProduct(w); }
  Eigen::VectorXd half_damp_solve(const Eigen::VectorXd& r, double h) const {
    return r.cwiseQuotient((1 + (h / 2) * rate->array()).matrix());
  }
  Eigen::VectorXd implicit_solve(const Eigen::VectorXd& r, double) const { return cg->solve(r); }
};

/// The amplification operator for Spectra: (y, w) stacked in one vector of 2n.
struct AmplificationOp {
  using Scalar = double;
  Integrator integrator;
  const VectorOps* ops;
  double h;
  Eigen::Index n;
  int power = 1;  ///< steps per product: G^power spreads clustered magnitudes apart
  Eigen::Index rows() const { return 2 * n; }
  Eigen::Index cols() const { return 2 * n; }
  void apply(const double* in, double* out) const {
    Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(in, n);
    Eigen::VectorXd w = Eigen::Map<const Eigen::VectorXd>(in + n, n);
    for (int k = 0; k < power; ++k) linear_step(integrator, *ops, h, y, w);
    Eigen::Map<Eigen::VectorXd>(out, n) = y;
    Eigen::Map<Eigen::VectorXd>(out + n, n) = w;
  }
  void perform_op(const double* in, double* out) const { apply(in, out); }
};

/// rho estimated by the growth of ||G^k u|| over many steps: the fallback when Arnoldi does
/// not converge (clustered magnitudes). Averages over the last half of the steps.
double power_growth(const AmplificationOp& op, int steps) {
  Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(op.rows(), 0.3, 1.7).array().sin();
  Eigen::VectorXd next(op.rows());
  double log_growth = 0;
  for (int k = 0; k < steps; ++k) {
    u /= u.norm();
    op.apply(u.data(), next.data());
    if (k >= steps / 2) log_growth += std::log(next.norm());
    u.swap(next);
  }
  return std::exp(log_growth / (steps - steps / 2));
}

}  // namespace

Eigen::Matrix2d mode_amplification(Integrator integrator, double lambda, double c, double h) {
  const ScalarOps ops{lambda, c};
  Eigen::Matrix2d G;
  for (int col = 0; col < 2; ++col) {
    double y = col == 0 ? 1 : 0, w = col == 1 ? 1 : 0;
    linear_step(integrator, ops, h, y, w);
    G(0, col) = y;
    G(1, col) = w;
  }
  return G;
}

double mode_spectral_radius(Integrator integrator, double lambda, double c, double h) {
  const Eigen::Matrix2d G = mode_amplification(integrator, lambda, c, h);
  const double tr = G.trace(), det = G.determinant();
  // tr^2 - 4 det, written without its cancellation: a mode near lambda = 0 has the real pair
  // 1 and about 1 - c h, and at small h tr^2 and 4 det agree to 1e-14 and more, so their
  // difference's rounding (1e-16 of tr^2) put the radius above 1 + 1e-12 (uniform_dt_max
  // then gave 7.7e-7 s on two-node, whose step is stable up to 2 s).
  const double gap = G(0, 0) - G(1, 1);
  const double disc = gap * gap + 4 * G(0, 1) * G(1, 0);
  if (disc >= 0) return (std::abs(tr) + std::sqrt(disc)) / 2;  // real pair: max |z|
  return std::sqrt(det);                                        // complex pair: |z|^2 = det
}

namespace {

/// RK4 (SPEC 7's classic step), underdamped modes: the step's eigenvalues are R(z), z = h mu,
/// mu = -c/2 +- i w the roots of mu^2 + c mu + lambda, R(z) = sum_{k<=4} z^k/k!. With
/// x = -c h/2 and Y = h^2 (lambda - c^2/4) = (Im z)^2, Taylor's expansion of R about x gives
///   |R(x + i y)|^2 = P(Y) = (R(x) - R''(x) Y/2 + Y^2/24)^2 + Y (R'(x) - R'''(x) Y/6)^2,
/// a quartic in Y. rk4_quartic gives its coefficients p_j at x, and with `magnitude` the
/// same formulas with every term's magnitude (x -> |x|, differences -> sums), which bound
/// each p_j's rounding. Both certificates below evaluate in long double, each sum with a
/// generous allowance (1e-14 of the sum of its terms' magnitudes).
/// P's coefficients as polynomials in x: c[j][i] multiplies x^i Y^j (degree 8 - 2j in x);
/// with `magnitude` the same products of the terms' magnitudes (every coefficient >= 0).
struct QuarticInX {
  long double c[5][9] = {};
};
QuarticInX rk4_quartic_in_x(bool magnitude) {
  using Poly = std::vector<long double>;
  auto mul = [](const Poly& a, const Poly& b, long double k) {
    Poly r(a.size() + b.size() - 1, 0);
    for (size_t i = 0; i < a.size(); ++i)
      for (size_t j = 0; j < b.size(); ++j) r[i + j] += k * a[i] * b[j];
    return r;
  };
  auto add = [](Poly a, const Poly& b) {
    if (b.size() > a.size()) a.resize(b.size(), 0);
    for (size_t i = 0; i < b.size(); ++i) a[i] += b[i];
    return a;
  };
  const long double s = magnitude ? 1 : -1;
  // rk4_quartic's a0 = R, a1 = -R''/2, a2 = 1/24, b0 = R', b1 = -R'''/6, in powers of x.
  const Poly a0 = {1, 1, 1.0L / 2, 1.0L / 6, 1.0L / 24}, b0 = {1, 1, 1.0L / 2, 1.0L / 6};
  const Poly a1 = {s / 2, s / 2, s / 4}, a2 = {1.0L / 24}, b1 = {s / 6, s / 6};
  const Poly p[5] = {mul(a0, a0, 1), add(mul(a0, a1, 2), mul(b0, b0, 1)),
                     add(add(mul(a1, a1, 1), mul(a0, a2, 2)), mul(b0, b1, 2)),
                     add(mul(a1, a2, 2), mul(b1, b1, 1)), mul(a2, a2, 1)};
  QuarticInX q;
  for (int j = 0; j <= 4; ++j)
    for (size_t i = 0; i < p[j].size(); ++i) q.c[j][i] = p[j][i];
  return q;
}

/// P's coefficients p_j at x (with `magnitude`, the magnitudes' at |x|), from the table.
struct Quartic {
  long double c[5];
};
Quartic rk4_quartic(long double x, bool magnitude) {
  static const QuarticInX p = rk4_quartic_in_x(false), m = rk4_quartic_in_x(true);
  const QuarticInX& q = magnitude ? m : p;
  Quartic r{};
  for (int j = 0; j <= 4; ++j)
    for (int i = 8; i >= 0; --i) r.c[j] = r.c[j] * x + q.c[j][i];  // Horner
  return r;
}

/// C(n, k) for n and k up to 8 (0 outside 0 <= k <= n).
long double choose(int n, int k) {
  if (k < 0 || k > n) return 0;
  long double r = 1;
  for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
  return r;
}

/// The allowance for a long double sum of terms whose magnitudes add to `size` (long double
/// rounds at 5e-20; the rates and steps the quartic starts from are doubles).
long double allowance(long double size) { return 1e-14L * size; }

/// Q(s) = P(Y0 + s) - (1 + eps)^2 is positive for every s >= 0 when its constant term is and
/// none of its other Taylor coefficients is negative: the certificate that every mode with
/// Y >= Y0 has radius above 1 + eps.
bool rk4_unstable_beyond(long double x, long double Y0, long double e1) {
  const Quartic p = rk4_quartic(x, false), m = rk4_quartic(std::abs(x), true);
  for (int k = 0; k <= 4; ++k) {  // q_k = sum_j C(j, k) p_j Y0^(j - k)
    long double q = k == 0 ? -e1 * e1 : 0, size = k == 0 ? e1 * e1 : 0;
    long double power = 1;
    for (int j = k; j <= 4; ++j) {
      q += choose(j, k) * p.c[j] * power;
      size += choose(j, k) * m.c[j] * power;
      power *= Y0;
    }
    if (k == 0 ? !(q > allowance(size)) : !(q >= allowance(size))) return false;
  }
  return true;
}

/// The smallest lambda (>= c^2/4) from which RK4 is certified unstable at rate c and step h:
/// the certificate holds from some Y on (for large Y every coefficient is positive) and,
/// once it holds, at every larger Y (a forward shift keeps the coefficients non-negative), so
/// bisection finds where it starts; the end returned is one where it was checked.
double rk4_lambda_from(double c, double h, double e1) {
  const long double x = -static_cast<long double>(c) * h / 2;
  if (rk4_unstable_beyond(x, 0, e1)) return c * c / 4 * kRoundUp;
  long double lo = 0, hi = 16;
  while (!rk4_unstable_beyond(x, hi, e1)) {
    lo = hi;
    hi *= 2;
    if (hi > 1e12L) return kInf;
  }
  for (int k = 0; k < 200 && hi - lo > 1e-18L * hi; ++k) {
    const long double mid = (lo + hi) / 2;
    (rk4_unstable_beyond(x, mid, e1) ? hi : lo) = mid;
  }
  const long double lambda = static_cast<long double>(c) * c / 4 + hi / (static_cast<long double>(h) * h);
  return static_cast<double>(lambda) * kRoundUp;
}

/// RK4's stable side: every mode with lambda in [0, lambda_hi] has both step eigenvalues
/// within 1 + eps.
/// - Real roots (lambda <= c^2/4) give z = h mu in [-c h, 0]. There R(x) - 1 = x g(x) with
///   g(x) = 1 + x/2 + x^2/6 + x^3/24, increasing (g' = 1/2 + x/3 + x^2/8 has no real root)
///   and positive at -kRk4RealEnd = -2.78529 (1.9e-6, exactly in rationals), so R(x) <= 1 on
///   [-2.78529, 0]; and R > 0 everywhere (at a critical point R = R' + x^4/24 = x^4/24, and
///   x = 0 is none). So c h <= 2.78529 covers them (RK4's real interval ends at -2.7852936).
/// - Complex roots (lambda > c^2/4): Q = P - (1 + eps)^2 <= 0 at x = -c h/2 for every
///   Y = h^2 (lambda - c^2/4) up to h^2 (lambda_hi - c^2/4), by Bernstein coefficients
///   (rk4_box_stable, below): over a box of steps or of rates, a single (c, h) being the box
///   of one rate.
constexpr long double kRk4RealEnd = 2.78529L;

/// A box of RK4's complex roots: one parameter p in [p0, p1] (the step at a fixed rate, or
/// the rate at a fixed step) and v = lambda - c^2/4 in [0, V], with x = -alpha p and
/// Y = beta p^(2 e) v:
///   the step h:  alpha = c/2, beta = 1,   e = 1  (Y = h^2 v);
///   the rate c:  alpha = h/2, beta = h^2, e = 0.
/// Q = P - (1 + eps)^2 is then a polynomial in (p, v) of degree at most 8 and 4.
struct Rk4Box {
  long double alpha, beta;
  int e;
  long double p0, p1, V;
};

/// On the box, (t, s) = ((p - p0)/(p1 - p0), v/V), every tensor Bernstein coefficient of Q
/// below minus its allowance proves Q <= 0 there.
bool rk4_box_stable(const QuarticInX& p, const QuarticInX& m, const Rk4Box& box, long double e1) {
  // Q = sum_{k, j} A[k][j] p^k v^j, k = i + 2 e j; S: the terms' magnitudes.
  long double A[9][5] = {}, S[9][5] = {};
  long double beta_j = 1;
  for (int j = 0; j <= 4; ++j, beta_j *= box.beta) {
    long double power = 1;  // alpha^i
    for (int i = 0; i + 2 * box.e * j <= 8 && i <= 8 - 2 * j; ++i, power *= box.alpha) {
      A[i + 2 * box.e * j][j] += p.c[j][i] * (i % 2 ? -power : power) * beta_j;
      S[i + 2 * box.e * j][j] += m.c[j][i] * power * beta_j;
    }
  }
  // p = p0 + w t, v = V s: B[q][j] = sum_{k >= q} A[k][j] C(k, q) p0^(k - q) w^q V^j.
  const long double w = box.p1 - box.p0;
  long double B[9][5] = {}, T[9][5] = {};
  long double wq = 1;
  for (int q = 0; q <= 8; ++q, wq *= w) {
    long double vj = 1;
    for (int j = 0; j <= 4; ++j, vj *= box.V) {
      long double b = 0, t = 0, power = 1;
      for (int k = q; k <= 8; ++k, power *= box.p0) {
        b += A[k][j] * choose(k, q) * power;
        t += S[k][j] * choose(k, q) * power;
      }
      B[q][j] = b * wq * vj;
      T[q][j] = t * wq * vj;
    }
  }
  B[0][0] -= e1 * e1;
  T[0][0] += e1 * e1;
  for (int M = 0; M <= 8; ++M)
    for (int N = 0; N <= 4; ++N) {
      long double beta = 0, size = 0;
      for (int q = 0; q <= M; ++q)
        for (int j = 0; j <= N; ++j) {
          const long double weight = choose(M, q) / choose(8, q) * choose(N, j) / choose(4, j);
          beta += weight * B[q][j];
          size += weight * T[q][j];
        }
      if (!(beta + allowance(size) <= 0)) return false;
    }
  return true;
}

/// Every p in [p0, p1] and every mode in [0, lambda_hi]: the real roots by c h <= 2.78529 at
/// the box's largest c h (kRk4RealEnd), the complex ones by rk4_box_stable, halved in p
/// where a box does not close (at most 64 pieces). A piece's V is lambda_hi less its
/// smallest c^2/4 (for the rate, an over-cover: lambda up to lambda_hi + (c^2 - c0^2)/4).
bool rk4_stable_over(double lambda_hi, Rk4Box box, long double e1) {
  const bool step = box.e == 1;
  const long double c_hi = step ? 2 * box.alpha : box.p1, h_hi = step ? box.p1 : 2 * box.alpha;
  if (!(c_hi * h_hi * (1 + 1e-15L) <= kRk4RealEnd)) return false;
  static const QuarticInX p = rk4_quartic_in_x(false), m = rk4_quartic_in_x(true);
  std::vector<Rk4Box> todo{box};
  for (int pieces = 0; !todo.empty(); ++pieces) {
    if (pieces == 64) return false;
    Rk4Box b = todo.back();
    todo.pop_back();
    const long double c_lo = step ? 2 * b.alpha : b.p0;
    b.V = (lambda_hi - c_lo * c_lo / 4) * (1 + 1e-15L);
    if (!(b.V > 0) || rk4_box_stable(p, m, b, e1)) continue;  // V <= 0: real roots only
    const long double mid = (b.p0 + b.p1) / 2;
    todo.push_back({b.alpha, b.beta, b.e, b.p0, mid, 0});
    todo.push_back({b.alpha, b.beta, b.e, mid, b.p1, 0});
  }
  return true;
}

/// Every step in (0, S] at rate c.
bool rk4_stable_up_to(double lambda_hi, double c, double S, long double e1) {
  return rk4_stable_over(lambda_hi, {static_cast<long double>(c) / 2, 1, 1, 0, S, 0}, e1);
}

/// Every rate in [c0, c1] at step h.
bool rk4_rates_stable(double lambda_hi, double h, double c0, double c1, long double e1) {
  const long double hl = h;
  return rk4_stable_over(lambda_hi, {hl / 2, hl * hl, 0, c0, c1, 0}, e1);
}

/// The rates proved stable at step h around c: [lo, c] and [c, hi], each side's end by
/// bisection (to 1e-10) from c toward 0 and toward the real roots' cap 2.78529/h; none
/// (lo > hi) when c itself is not proved.
std::pair<double, double> rk4_rate_range(double lambda_hi, double c, double h, long double e1) {
  if (!rk4_rates_stable(lambda_hi, h, c, c, e1)) return {kInf, -kInf};
  auto bisect = [&](double good, double bad, auto proved) {
    for (int k = 0; k < 60 && std::abs(bad - good) > 1e-10 * std::abs(bad); ++k) {
      const double mid = (good + bad) / 2;
      (proved(mid) ? good : bad) = mid;
    }
    return good;
  };
  auto up = [&](double C) { return rk4_rates_stable(lambda_hi, h, c, C, e1); };
  auto down = [&](double C) { return rk4_rates_stable(lambda_hi, h, C, c, e1); };
  const double cap =
      static_cast<double>(kRk4RealEnd / (static_cast<long double>(h) * (1 + 1e-14L)));
  const double hi = up(cap) ? cap : bisect(c, cap, up);
  const double lo = c == 0 || down(0) ? 0 : bisect(c, 0, down);
  return {lo, hi};
}

/// The largest S (by doubling, then bisection) that rk4_stable_up_to proves; 0 when none is.
double rk4_dt_up_to(double lambda_hi, double c, long double e1) {
  auto proved = [&](double S) { return rk4_stable_up_to(lambda_hi, c, S, e1); };
  double lo = 0, hi = 0.5 / std::sqrt(std::max({lambda_hi, c * c, 1e-300}));
  for (int k = 0; k < 60 && proved(hi); ++k) {
    lo = hi;
    hi *= 2;
  }
  if (lo == 0) {
    for (int k = 0; k < 60 && !proved(hi); ++k) hi /= 2;
    if (!proved(hi)) return 0;
    lo = hi;
    hi *= 2;
  }
  for (int k = 0; k < 50 && hi - lo > 1e-10 * hi; ++k) {
    const double mid = (lo + hi) / 2;
    (proved(mid) ? lo : hi) = mid;
  }
  return lo;
}

}  // namespace

ModeInstability mode_instability(Integrator integrator, double lambda_0, double c, double h) {
  ModeInstability m;
  if (integrator == Integrator::rk4) {
    m.lambda_from = rk4_lambda_from(c, h, 1 + kMarginal);
    return m;
  }
  if (integrator != Integrator::forward_euler && integrator != Integrator::verlet) return m;
  // (1 + eps)^2 - 1 and (2 + eps)^2, rounded up (e1 - 1 is exact).
  const double e1 = 1 + kMarginal, grow = (e1 - 1) * (e1 + 1) * kRoundUp;
  const double C = (e1 + 1) * (e1 + 1) * kRoundUp;
  if (integrator == Integrator::forward_euler) {
    // d > (1 + eps)^2  <=>  h^2 lambda - c h - grow > 0.
    m.lambda_from = (c * h + grow) / (h * h) * kRoundUp;
    m.dt_from = lambda_0 > 0 ? (c + std::sqrt(c * c + 4 * lambda_0 * grow)) / (2 * lambda_0) * kRoundUp
                             : kInf;
    const double r = (h * h * lambda_0 - grow) / h;
    m.rate_below = r > 0 ? r / kRoundUp : -kInf;
    return m;
  }
  // Verlet, with q = 1 - h^2 lambda/2 < -1: (1 + c h/2)(z^2 - |t| z + d) at z = 1 + eps is
  // (1 + eps)^2 (1 + c h/2) + (1 - c h/2) - 2 (1 + eps)(h^2 lambda/2 - 1) < 0, that is
  // A h^2 - B h - C > 0 with A = (1 + eps) lambda, B = c grow/2, C = (2 + eps)^2; from
  // lambda_from on, q <= 1 - C/(2 (1 + eps)) < -1.
  m.lambda_from = (C + c * grow / 2 * h) / (e1 * h * h) * kRoundUp;
  const double A = e1 * lambda_0, B = c * grow / 2;
  m.dt_from = A > 0 ? (B + std::sqrt(B * B + 4 * A * C)) / (2 * A) * kRoundUp : kInf;
  const double r = (A * h * h - C) / (h * grow / 2);
  m.rate_below = r > 0 ? r / kRoundUp : -kInf;
  return m;
}

ModeStability mode_stability(Integrator integrator, double lambda_hi, double c, double h) {
  ModeStability m;
  if (integrator == Integrator::rk4) {
    m.proved = true;
    std::tie(m.rate_lo, m.rate_hi) = rk4_rate_range(lambda_hi, c, h, 1 + kMarginal);
    m.stable = m.rate_lo <= m.rate_hi;  // c's own proof, the box [c, c]
    m.dt_up_to = rk4_dt_up_to(lambda_hi, c, 1 + kMarginal);
    return m;
  }
  if (integrator != Integrator::forward_euler && integrator != Integrator::verlet) return m;
  m.proved = true;
  if (integrator == Integrator::forward_euler) {
    m.stable = c * h * kRoundUp <= 2 && lambda_hi * h * kRoundUp <= c;
    m.dt_up_to = c > 0 ? std::min(c / lambda_hi, 2 / c) / kRoundUp : 0;
    m.rate_lo = h * lambda_hi * kRoundUp;
    m.rate_hi = 2 / h / kRoundUp;
    return m;
  }
  m.stable = lambda_hi * h * h * kRoundUp <= 4;
  m.dt_up_to = 2 / std::sqrt(lambda_hi) / kRoundUp;
  m.rate_lo = 0;
  m.rate_hi = m.stable ? kInf : -kInf;
  return m;
}

double spectrum_spectral_radius(Integrator integrator, const StiffnessSpectrum& s, double c,
                                double h) {
  double rho = 0;
  const int samples = s.lambda_max > s.lambda_min ? 64 : 1;
  for (int k = 0; k <= samples; ++k) {
    const double lambda = s.lambda_min + (s.lambda_max - s.lambda_min) * k / samples;
    rho = std::max(rho, mode_spectral_radius(integrator, lambda, c, h));
  }
  return rho;
}

double uniform_dt_max(Integrator integrator, const StiffnessSpectrum& s, double c) {
  if (integrator == Integrator::implicit_euler) return kInf;
  if (integrator == Integrator::semi_implicit_euler) return semi_implicit_dt_max(s.lambda_max, c);
  // Undamped forward Euler: |z|^2 = 1 + lambda h^2 > 1 for every h > 0 and lambda > 0.
  if (integrator == Integrator::forward_euler && c <= 0 && s.lambda_max > 0) return 0;
  auto stable = [&](double h) { return spectrum_spectral_radius(integrator, s, c, h) <= 1 + kMarginal; };
  const double scale = 1.0 / std::sqrt(std::max({s.lambda_max, c * c, 1e-300}));
  double lo = 1e-6 * scale;
  if (!stable(lo)) return 0;
  double hi = lo;
  while (stable(hi)) {
    lo = hi;
    hi *= 1.25;
    if (hi > 1e6 * scale) return kInf;
  }
  for (int k = 0; k < 200 && hi - lo > 1e-13 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (stable(mid) ? lo : hi) = mid;
  }
  return lo;
}

RateInterval uniform_rate_interval(Integrator integrator, const StiffnessSpectrum& s, double h) {
  if (integrator == Integrator::implicit_euler) return {0, kInf};
  if (integrator == Integrator::semi_implicit_euler)  // SPEC 7; empty when lambda h^2 >= 4
    return {0, std::max(0.0, (4 - s.lambda_max * h * h) / (2 * h))};
  auto stable = [&](double c) { return spectrum_spectral_radius(integrator, s, c, h) <= 1 + kMarginal; };
  // No explicit step damps a mode with c h > 8; sample [0, 8/h] and refine the first run.
  const int samples = 2000;
  const double cap = 8 / h;
  int first = -1, last = -1;
  for (int k = 0; k <= samples; ++k) {
    const bool ok = stable(cap * k / samples);
    if (ok && first < 0) first = k;
    if (ok) last = k;
    if (!ok && first >= 0) break;
  }
  if (first < 0) return {0, 0};
  auto refine = [&](double good, double bad) {
    for (int k = 0; k < 200 && std::abs(bad - good) > 1e-13 * std::abs(bad); ++k) {
      const double mid = 0.5 * (good + bad);
      (stable(mid) ? good : bad) = mid;
    }
    return good;
  };
  RateInterval r;
  r.lo = first == 0 ? 0 : refine(cap * first / samples, cap * (first - 1) / samples);
  r.hi = last == samples ? kInf : refine(cap * last / samples, cap * (last + 1) / samples);
  return r;
}

Eigen::VectorXd damping_rates(const Model& model, const std::vector<double>& gamma) {
  std::vector<double> rates;
  for (size_t i = 0; i < model.rest.size(); ++i)
    if (!model.fixed[i])
      for (int r = 0; r < 3; ++r) rates.push_back(gamma[i] / model.mass[i]);
  return Eigen::Map<Eigen::VectorXd>(rates.data(), static_cast<Eigen::Index>(rates.size()));
}

SpectralRadius amplification_spectral_radius(Integrator integrator,
                                             const SparseMatrix& K_weighted,
                                             const Eigen::VectorXd& rate, double h) {
  const Eigen::Index n = K_weighted.rows();
  if (n == 0) return {0, true};
  if (2 * n <= 24) {  // tiny: the dense matrix is exact and cheap
    const Eigen::MatrixXd G = amplification_matrix_dense(integrator, K_weighted, rate, h);
    return {G.eigenvalues().cwiseAbs().maxCoeff(), true};
  }
  const VectorOps ops(integrator, K_weighted, rate, h);
  // Arnoldi on G^4: |z|^4 spreads the magnitudes of lightly damped modes, which all sit near
  // the circle |z| = sqrt(1 - c h), four times further apart, for the price of cheap products.
  AmplificationOp op{integrator, &ops, h, n, 4};
  const Eigen::Index ncv = std::min<Eigen::Index>(2 * n, 40);
  Spectra::GenEigsSolver<AmplificationOp> eigs(op, 4, ncv);
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestMagn, 200, 1e-8);
  if (eigs.info() == Spectra::CompInfo::Successful)
    return {std::pow(eigs.eigenvalues().cwiseAbs().maxCoeff(), 1.0 / op.power), true};
  return {std::pow(power_growth(op, 200), 1.0 / op.power), false};
}

Eigen::MatrixXd amplification_matrix_dense(Integrator integrator, const SparseMatrix& K_weighted,
                                           const Eigen::VectorXd& rate, double h) {
  const Eigen::Index n = K_weighted.rows();
  const VectorOps ops(integrator, K_weighted, rate, h);
  const AmplificationOp op{integrator, &ops, h, n};
  Eigen::MatrixXd G(2 * n, 2 * n);
  Eigen::VectorXd e = Eigen::VectorXd::Zero(2 * n), col(2 * n);
  for (Eigen::Index k = 0; k < 2 * n; ++k) {
    e(k) = 1;
    op.apply(e.data(), col.data());
    G.col(k) = col;
    e(k) = 0;
  }
  return G;
}

}  // namespace dampbound
