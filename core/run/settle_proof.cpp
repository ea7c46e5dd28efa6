// The scene's constants of SPEC 8's early stop: eligibility, the spectrum bounds of G by
// Gershgorin's theorem, degrees, lengths (docs/settled.md, "The proof", step 1).
#include "core/run/settle_proof.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <utility>

namespace dampbound {

namespace {

std::atomic<bool> g_enabled{true};
std::atomic<double> g_widen{1.0};

bool all_equal_free(const std::vector<double>& v, const std::vector<std::uint8_t>& fixed,
                    double& value) {
  bool first = true;
  for (size_t i = 0; i < v.size(); ++i) {
    if (fixed[i]) continue;
    if (first) value = v[i], first = false;
    if (v[i] != value) return false;
  }
  return !first;
}

}  // namespace

void set_settle_proof_enabled(bool on) { g_enabled = on; }
bool settle_proof_enabled() { return g_enabled; }
void set_settle_proof_widen(double factor) { g_widen = factor; }

settle::SceneBound settle_scene_bound(const ModelSpec& mo, const std::vector<double>& x0,
                                      const std::vector<double>& v0, Integrator integrator,
                                      DampingPolicy policy, bool other_damping, bool cuts,
                                      std::optional<std::string>* why_not) {
  settle::SceneBound g;
  auto refuse = [&](const char* why) {
    if (why_not) *why_not = why;
    g.eligible = false;
    return g;
  };
  if (!settle_proof_enabled()) return refuse("the early stop is turned off");
  if (integrator != Integrator::semi_implicit_euler) return refuse("not the paper's step");
  if (policy != DampingPolicy::fixed) return refuse("the policy chooses gamma from the state");
  if (other_damping) return refuse("dashpot or Rayleigh damping");
  if (cuts) return refuse("the scene cuts springs");
  const size_t n = mo.rest.size();
  if (!all_equal_free(mo.mass_scale, mo.fixed, g.mass_scale)) return refuse("non-uniform masses");
  if (!all_equal_free(mo.gamma_scale, mo.fixed, g.gamma_scale))
    return refuse("non-uniform gamma");
  g.mu_lo = HUGE_VAL;
  std::vector<double> row(3 * n, 0.0);  // Gershgorin: sum over a free row of |G_rc|
  std::vector<double> degree(n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) {
      g.x_max = std::max(g.x_max, std::fabs(mo.rest[i][c]));
      const size_t k = 3 * i + static_cast<size_t>(c);
      if (mo.fixed[i] ? (x0[k] != mo.rest[i][c] || v0[k] != 0) : mo.external_force[i][c] != 0)
        return refuse(mo.fixed[i] ? "a fixed node starts away from rest"
                                  : "an external force");
    }
    if (mo.fixed[i]) continue;
    if (!(mo.anchor_scale[i] > 0)) return refuse("a free node without an anchor");
    g.mu_lo = std::min(g.mu_lo, mo.anchor_scale[i]);
    g.anchor_max = std::max(g.anchor_max, mo.anchor_scale[i]);
    for (int c = 0; c < 3; ++c) row[3 * i + static_cast<size_t>(c)] = mo.anchor_scale[i];
    g.coords += 3;
  }
  if (g.coords == 0) return refuse("no free node");
  g.l0_min = HUGE_VAL;
  for (const Spring& sp : mo.springs) {
    const size_t i = static_cast<size_t>(sp.i), j = static_cast<size_t>(sp.j);
    if (mo.fixed[i] && mo.fixed[j]) continue;
    double e[3];
    const double xi[3] = {mo.rest[i][0], mo.rest[i][1], mo.rest[i][2]};
    const double xj[3] = {mo.rest[j][0], mo.rest[j][1], mo.rest[j][2]};
    const double l = spring_vector(xi, xj, e);
    // The rest state is an equilibrium (up to the rounding the proof allows for) only where
    // every spring's rest length is its length there.
    if (!(sp.rest_length > 0) || l != sp.rest_length)
      return refuse("a spring not at its rest length at rest");
    g.l0_min = std::min(g.l0_min, sp.rest_length);
    g.l0_max = std::max(g.l0_max, sp.rest_length);
    g.k_max = std::max(g.k_max, sp.kappa_scale);
    double d_abs = 0;
    for (int c = 0; c < 3; ++c) d_abs += std::fabs(e[c] / l);
    for (size_t a : {i, j}) {
      if (mo.fixed[a]) continue;
      degree[a] += 1;
      const double blocks = (mo.fixed[i] || mo.fixed[j]) ? 1.0 : 2.0;  // diagonal, off-diagonal
      for (int c = 0; c < 3; ++c)
        row[3 * a + static_cast<size_t>(c)] += sp.kappa_scale * std::fabs(e[c] / l) * d_abs * blocks;
    }
  }
  if (g.k_max == 0) g.l0_min = g.l0_max = 1;  // anchors only: no nonlinear remainder
  // Step 4's spread: |R_i| <= C sum_{s at i} (a_i + a_j)^2 <= C ((1 + e) deg_i a_i^2 +
  // (1 + 1/e) sum_j Adj_ij a_j^2) = C (M_e p)_i with p = a^2 (a_i = |u_i|), sum p = |u|^2 <=
  // U^2; |M_e p|_2 is convex in p, so at most U^2 max_k |M_e e_k|_2, with
  // |M_e e_k|_2^2 = ((1 + e) deg_k)^2 + (1 + 1/e)^2 sum_j Adj_jk^2 over free j.
  std::vector<std::pair<int, int>> pairs;
  for (const Spring& sp : mo.springs)
    if (!mo.fixed[static_cast<size_t>(sp.i)] || !mo.fixed[static_cast<size_t>(sp.j)])
      pairs.emplace_back(std::min(sp.i, sp.j), std::max(sp.i, sp.j));
  std::sort(pairs.begin(), pairs.end());
  std::vector<double> adj_sq(n, 0.0);  // sum_j Adj_jk^2 over free neighbours j of k
  for (size_t a = 0; a < pairs.size();) {
    size_t b = a;
    while (b < pairs.size() && pairs[b] == pairs[a]) ++b;
    const double mult = static_cast<double>(b - a);
    const size_t i = static_cast<size_t>(pairs[a].first), j = static_cast<size_t>(pairs[a].second);
    if (!mo.fixed[i] && !mo.fixed[j]) {
      adj_sq[i] += mult * mult;
      adj_sq[j] += mult * mult;
    }
    a = b;
  }
  g.spread = HUGE_VAL;
  for (int k = 1; k <= 40; ++k) {
    const double e = 0.05 * k;
    double worst = 0;
    for (size_t i = 0; i < n; ++i) {
      if (mo.fixed[i]) continue;
      const double diag = (1.0 + e) * degree[i], off = 1.0 + 1.0 / e;
      worst = std::max(worst, std::sqrt(diag * diag + off * off * adj_sq[i]));
    }
    g.spread = std::min(g.spread, worst);
  }
  g.spread *= 1.0 + 1e-12;
  for (size_t i = 0; i < n; ++i) {
    if (mo.fixed[i]) continue;
    g.degree = std::max(g.degree, degree[i]);
    for (int c = 0; c < 3; ++c) g.mu_hi = std::max(g.mu_hi, row[3 * i + static_cast<size_t>(c)]);
  }
  g.mu_hi *= 1.0 + 1e-12;  // the row sums' own rounding (a few units of 2^-53)
  g.nodes = static_cast<double>(n);
  g.springs = static_cast<double>(mo.springs.size());
  g.eligible = true;
  if (why_not) why_not->reset();
  return g;
}

SettleProof::SettleProof(const ModelSpec& mo, const std::vector<double>& x0,
                         const std::vector<double>& v0, Integrator integrator,
                         DampingPolicy policy, bool other_damping, bool cuts) {
  bound_ = settle_scene_bound(mo, x0, v0, integrator, policy, other_damping, cuts, &why_not_);
  if (!bound_.eligible) return;
  for (const Spring& sp : mo.springs) {
    spring_i_.push_back(sp.i);
    spring_j_.push_back(sp.j);
    kappa_scale_.push_back(sp.kappa_scale);
  }
  for (const Vec3& r : mo.rest)
    for (int c = 0; c < 3; ++c) rest_.push_back(r[c]);
  anchor_scale_ = mo.anchor_scale;
  fixed_.assign(mo.fixed.begin(), mo.fixed.end());
  settle::SceneArrays a = arrays();
  a.direction = nullptr;
  for (int k = 0; k < a.springs; ++k) {
    double d[3];
    settle::rest_direction(a, k, d);
    for (double x : d) direction_.push_back(x);
  }
}

settle::SceneArrays SettleProof::arrays() const {
  settle::SceneArrays a;
  a.nodes = static_cast<int>(fixed_.size());
  a.springs = static_cast<int>(spring_i_.size());
  a.spring_i = spring_i_.data();
  a.spring_j = spring_j_.data();
  a.kappa_scale = kappa_scale_.data();
  a.rest = rest_.data();
  a.anchor_scale = anchor_scale_.data();
  a.fixed = fixed_.data();
  a.direction = direction_.empty() ? nullptr : direction_.data();
  return a;
}

settle::TrialBound SettleProof::trial(double m, double kappa, double gamma, double dt,
                                      const StopRules& rules) const {
  return settle::trial_bound(bound_, m, kappa, gamma, dt,
                             rules.restore_fraction * rules.reference, g_widen);
}

}  // namespace dampbound
