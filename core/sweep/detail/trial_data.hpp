#pragma once
// What the trial body (core/sweep/detail/trial_body.hpp) reads: the scene as flat arrays and a
// trial's constants, plain data that the GPU sweep copies to the device as it is.
// core/sweep/flat_model.cpp fills both from a SceneSpec and a TrialParams.
#include "core/run/detail/settle_bound.hpp"
#include "dampbound/physics/params.hpp"
#include "dampbound/run/verdict.hpp"

namespace dampbound::trial_body {

/// The scene (ModelSpec, initial state, policy, integrator, stop rules) as arrays. Per node:
/// rest, x0, v0, ext (3 each), the scales, fixed; per spring: its ends, rest length, stiffness
/// and dashpot scales, in list order; compile_model()'s incidence lists (each node's springs
/// in list order, ~k where the node is the spring's j end).
struct FlatModel {
  int nodes = 0, springs = 0;
  const int* spring_i = nullptr;
  const int* spring_j = nullptr;
  const double* rest_length = nullptr;
  const double* kappa_scale = nullptr;
  const double* kd_scale = nullptr;
  const int* incident_offset = nullptr;  // nodes + 1
  const int* incident = nullptr;
  const double* rest = nullptr;
  const double* x0 = nullptr;
  const double* v0 = nullptr;
  const double* ext = nullptr;
  const double* anchor_scale = nullptr;
  const double* anchor_kd_scale = nullptr;  // 1 where the scene gives none
  const double* mass_scale = nullptr;
  const double* gamma_scale = nullptr;
  /// kappa_i's scale (eq. 5): the largest incident stiffness scale, the anchor's included.
  const double* kappa_max_scale = nullptr;
  const unsigned char* fixed = nullptr;
  DampingPolicy policy = DampingPolicy::fixed;
  bool semi_implicit = true;  ///< else forward Euler
  bool uniform = true;        ///< every node has the same mass, gamma and kappa_i scales
  StopRules rules;
  /// SPEC 8's early stop: the scene's constants (not eligible unless the settled rule).
  settle::SceneBound settle;
};

/// A trial's values (TrialParams, SPEC 10's resolved against the scene) and what follows from
/// them once: m_i, m_i/dt, gamma_lo_i, gamma_i of a uniform scene (node 0's), and whether the
/// trial has dashpot or Rayleigh damping (compile_model()'s spring_damping).
struct TrialConsts {
  double m = 0, kappa = 0, gamma = 0, dt = 0, factor = 0;
  double kd = 0, alpha = 0, beta = 0;
  double mass = 0, md = 0, lo = 0, gu = 0;
  bool damped = false;
};

}  // namespace dampbound::trial_body
