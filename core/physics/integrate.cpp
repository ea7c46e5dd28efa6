#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
#include "core/physics/integrate.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <stdexcept>
#include <string>

#include "dampbound/physics/forces.hpp"
#include "dampbound/physics/step.hpp"
#include "dampbound/physics/stiffness.hpp"

namespace dampbound {

namespace {

/// F_i - D'_i: the internal force less SPEC 10's dashpot and Rayleigh force at t.
inline Vec3 net_force(const StepWorkspace& ws, size_t i) { return ws.force[i] - ws.damping[i]; }

/// Paper eqs. 3-4 (SPEC 2): a = (F - gamma v + f)/m; v += a dt; x += v_new dt. With SPEC 10's
/// damping D' (evaluated at t), a = (F - D' - gamma v + f)/m.
template <bool damped>
void semi_implicit_euler(const Model& model, double dt, State& s, StepWorkspace& ws) {
  ws.pass.threads.run(s.x.size(), [&](int, size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      if (model.spec().fixed[i]) continue;
      const Vec3 f = damped ? net_force(ws, i) : ws.force[i];
      const Vec3 a = (f - ws.gamma_eff[i] * s.v[i] + model.spec().external_force[i]) / model.mass[i];
      s.v[i] += a * dt;
      s.x[i] += s.v[i] * dt;
    }
  });
}

/// Forward (explicit) Euler: x += v_old dt; v += a dt.
template <bool damped>
void forward_euler(const Model& model, double dt, State& s, StepWorkspace& ws) {
  ws.pass.threads.run(s.x.size(), [&](int, size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      if (model.spec().fixed[i]) continue;
      const Vec3 f = damped ? net_force(ws, i) : ws.force[i];
      const Vec3 a = (f - ws.gamma_eff[i] * s.v[i] + model.spec().external_force[i]) / model.mass[i];
      s.x[i] += s.v[i] * dt;
      s.v[i] += a * dt;
    }
  });
}

/// a_i = (F_i - gamma_i v_i + f_i) / m_i with gamma_i held from the state at t.
inline Vec3 acceleration(const Model& model, const StepWorkspace& ws, size_t i, const Vec3& force,
                         const Vec3& v) {
  return (force - ws.gamma_eff[i] * v + model.spec().external_force[i]) / model.mass[i];
}

/// Velocity Verlet (central differences when undamped), damping held over the step:
///   v_h = v + (h/2) a(x, v)                                  (kick, damping explicit)
///   x'  = x + h v_h                                          (drift)
///   v'  = (v_h + (h/2)(F(x') + f)/m) / (1 + gamma h/(2m))    (kick, damping implicit)
/// The implicit half kick is a per-node division (Gamma is diagonal), so the step stays
/// explicit and is second order with damping too (trapezoidal on the damping term). One extra
/// force evaluation per step. Undamped, its exact limit is dt < 2/sqrt(lambda_max), as the
/// paper's step (both are leapfrog). SPEC 10's dashpot and Rayleigh force D' is explicit in
/// both half kicks: D'(x, v) in the first, D'(x', v_h) in the second (only Gamma is diagonal).
int verlet(const Model& model, double h, State& s, StepWorkspace& ws) {
  std::vector<Vec3>& force_new = ws.scratch[0];
  std::vector<Vec3>& damping_new = ws.scratch[1];
  const bool damped = !ws.damping.empty();
  for (size_t i = 0; i < s.x.size(); ++i) {
    if (model.spec().fixed[i]) continue;
    const Vec3 f = damped ? net_force(ws, i) : ws.force[i];
    s.v[i] += (h / 2) * acceleration(model, ws, i, f, s.v[i]);
    s.x[i] += h * s.v[i];
  }
  const int zero = internal_forces(model, s.x, force_new, &ws.pass);
  if (damped) {
    damping_forces(model, s.x, s.v, damping_new);
    for (size_t i = 0; i < s.x.size(); ++i) force_new[i] -= damping_new[i];
  }
  for (size_t i = 0; i < s.x.size(); ++i) {
    if (model.spec().fixed[i]) continue;
    const Vec3 kick = s.v[i] + (h / 2) * (force_new[i] + model.spec().external_force[i]) / model.mass[i];
    s.v[i] = kick / (1 + ws.gamma_eff[i] * h / (2 * model.mass[i]));
  }
  return zero;
}

/// Classic 4th-order Runge-Kutta on (x, v), x' = v, v' = a(x, v), damping held over the step:
/// k_s = (v_s, a(x + c_s h v_{s-1}, v + c_s h a_{s-1})), c = (0, 1/2, 1/2, 1),
/// (x, v) += h/6 (k_1 + 2 k_2 + 2 k_3 + k_4). Three extra force evaluations per step. SPEC 10's
/// dashpot and Rayleigh force is evaluated at each stage's (x, v), as the forces are.
int rk4(const Model& model, double h, State& s, StepWorkspace& ws) {
  std::vector<Vec3>& xt = ws.scratch[0];
  std::vector<Vec3>& ft = ws.scratch[1];
  std::vector<Vec3>& vk = ws.scratch[2];
  std::vector<Vec3>& ak = ws.scratch[3];
  std::vector<Vec3>& sum_v = ws.scratch[4];
  std::vector<Vec3>& sum_a = ws.scratch[5];
  std::vector<Vec3>& damping_stage = ws.scratch[6];
  const bool damped = !ws.damping.empty();
  const size_t n = s.x.size();
  xt = s.x;
  vk.resize(n);
  ak.resize(n);
  sum_v.resize(n);
  sum_a.resize(n);
  for (size_t i = 0; i < n; ++i) {
    vk[i] = s.v[i];
    ak[i] = model.spec().fixed[i] ? Vec3::Zero()
                           : acceleration(model, ws, i, damped ? net_force(ws, i) : ws.force[i],
                                          s.v[i]);
    sum_v[i] = vk[i];
    sum_a[i] = ak[i];
  }
  const double c[3] = {0.5, 0.5, 1.0}, weight[3] = {2, 2, 1};
  int zero = 0;
  for (int stage = 0; stage < 3; ++stage) {
    for (size_t i = 0; i < n; ++i)
      if (!model.spec().fixed[i]) xt[i] = s.x[i] + (c[stage] * h) * vk[i];
    zero += internal_forces(model, xt, ft, &ws.pass);
    for (size_t i = 0; i < n; ++i)
      if (!model.spec().fixed[i]) vk[i] = s.v[i] + (c[stage] * h) * ak[i];
    if (damped) {
      damping_forces(model, xt, vk, damping_stage);
      for (size_t i = 0; i < n; ++i) ft[i] -= damping_stage[i];
    }
    for (size_t i = 0; i < n; ++i) {
      if (model.spec().fixed[i]) continue;
      ak[i] = acceleration(model, ws, i, ft[i], vk[i]);
      sum_v[i] += weight[stage] * vk[i];
      sum_a[i] += weight[stage] * ak[i];
    }
  }
  for (size_t i = 0; i < n; ++i) {
    if (model.spec().fixed[i]) continue;
    s.x[i] += (h / 6) * sum_v[i];
    s.v[i] += (h / 6) * sum_a[i];
  }
  return zero;
}

/// Implicit (backward) Euler, one Newton step (Baraff & Witkin 1998, paper ref. [1]):
/// F(x') ~ F(x) - K (x' - x), x' = x + h v', so
///   (M + h Gamma + h^2 K) v' = M v + h (F(x) + f),   x' = x + h v'.
/// K is the tangent stiffness at x with compressed springs' (1 - l0/l) clamped at 0, so the
/// matrix is symmetric positive definite and conjugate gradients (Jacobi-preconditioned,
/// warm-started from v) solve it. Unconditionally stable on the linearised system. SPEC 10's
/// damping is implicit too: h C' joins the matrix, C' = alpha M + beta K + the dashpots
/// (spring_damping_matrix in stiffness.hpp, K clamped as above).
void implicit_euler(const Model& model, double h, State& s, StepWorkspace& ws) {
  int nfree = 0;
  const std::vector<int> block = free_blocks(model, &nfree);
  if (nfree == 0) return;
  SparseMatrix A = (h * h) * tangent_stiffness(model, s.x, true);
  if (model.spring_damping) A += h * spring_damping_matrix(model, s.x, true);
  Eigen::VectorXd rhs(3 * nfree), guess(3 * nfree);
  for (size_t i = 0; i < s.x.size(); ++i) {
    const int b = block[i];
    if (b < 0) continue;
    const Vec3 r = model.mass[i] * s.v[i] + h * (ws.force[i] + model.spec().external_force[i]);
    for (int k = 0; k < 3; ++k) {
      A.coeffRef(3 * b + k, 3 * b + k) += model.mass[i] + h * ws.gamma_eff[i];
      rhs(3 * b + k) = r(k);
      guess(3 * b + k) = s.v[i](k);
    }
  }
  Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper> cg;
  cg.setTolerance(1e-12);
  cg.compute(A);
  const Eigen::VectorXd v_new = cg.solveWithGuess(rhs, guess);
  for (size_t i = 0; i < s.x.size(); ++i) {
    const int b = block[i];
    if (b < 0) continue;
    s.v[i] = v_new.segment<3>(3 * b);
    s.x[i] += h * s.v[i];
  }
}

int semi_implicit_step(const Model& model, double dt, State& s, StepWorkspace& ws) {
  if (ws.damping.empty())
    semi_implicit_euler<false>(model, dt, s, ws);
  else
    semi_implicit_euler<true>(model, dt, s, ws);
  return 0;
}

int forward_euler_step(const Model& model, double dt, State& s, StepWorkspace& ws) {
  if (ws.damping.empty())
    forward_euler<false>(model, dt, s, ws);
  else
    forward_euler<true>(model, dt, s, ws);
  return 0;
}

int implicit_euler_step(const Model& model, double dt, State& s, StepWorkspace& ws) {
  implicit_euler(model, dt, s, ws);
  return 0;
}

}  // namespace

int advance(const Model& model, const Params& params, State& state, StepWorkspace& ws) {
  switch (params.integrator) {
    case Integrator::semi_implicit_euler: return semi_implicit_step(model, params.dt, state, ws);
    case Integrator::forward_euler: return forward_euler_step(model, params.dt, state, ws);
    case Integrator::verlet: return verlet(model, params.dt, state, ws);
    case Integrator::rk4: return rk4(model, params.dt, state, ws);
    case Integrator::implicit_euler: return implicit_euler_step(model, params.dt, state, ws);
  }
  throw std::invalid_argument("integrator " + std::to_string(static_cast<int>(params.integrator)) +
                              " has no step in integrate.cpp");
}

}  // namespace dampbound
