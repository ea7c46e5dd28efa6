// RK4's certificates for the per-mode proofs (docs/criteria.md, "Over the factorisation
// budget"): from which lambda every mode is unstable, and the steps and rates at which every
// mode in [0, lambda_hi] is stable. Long double sums, each with an allowance for its rounding.
#include "core/analysis/detail/rk4_proofs.hpp"
#include "core/physics/detail/numbers.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace dampbound::detail {
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
long double allowance(long double size) {
  return 1e-14L * size;
}

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

}  // namespace

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
  const long double lambda =
      static_cast<long double>(c) * c / 4 + hi / (static_cast<long double>(h) * h);
  return static_cast<double>(lambda) * kRoundUp;
}

namespace {

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

}  // namespace

/// The rates proved stable at step h around c: [lo, c] and [c, hi], each side's end by
/// bisection (to 1e-10) from c toward 0 and toward the real roots' cap 2.78529/h; none
/// (lo > hi) when c itself is not proved.
std::pair<double, double> rk4_rate_range(double lambda_hi, double c, double h, long double e1) {
  const double cap =
      static_cast<double>(kRk4RealEnd / (static_cast<long double>(h) * (1 + 1e-14L)));
  // The range grows from c, or, where c itself is not proved, from the proved one of
  // kRateSeeds - 1 rates evenly across (0, cap) nearest to it.
  constexpr int kRateSeeds = 32;
  double seed = c;
  if (!rk4_rates_stable(lambda_hi, h, c, c, e1)) {
    seed = std::numeric_limits<double>::quiet_NaN();
    for (int k = 1; k < kRateSeeds; ++k) {
      const double s = cap * k / kRateSeeds;
      if ((std::isnan(seed) || std::abs(s - c) < std::abs(seed - c)) &&
          rk4_rates_stable(lambda_hi, h, s, s, e1))
        seed = s;
    }
    if (std::isnan(seed)) return {kInf, -kInf};
  }
  auto bisect = [&](double good, double bad, auto proved) {
    for (int k = 0; k < 60 && std::abs(bad - good) > 1e-10 * std::abs(bad); ++k) {
      const double mid = (good + bad) / 2;
      (proved(mid) ? good : bad) = mid;
    }
    return good;
  };
  auto up = [&](double C) { return rk4_rates_stable(lambda_hi, h, seed, C, e1); };
  auto down = [&](double C) { return rk4_rates_stable(lambda_hi, h, C, seed, e1); };
  const double hi = up(cap) ? cap : bisect(seed, cap, up);
  const double lo = seed == 0 || down(0) ? 0 : bisect(seed, 0, down);
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

}  // namespace dampbound::detail
