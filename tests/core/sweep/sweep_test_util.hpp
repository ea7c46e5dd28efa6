#pragma once
// Shared helpers of the sweep tests: a small grid on a shipped scene.
#include <string>

#include "core/io/scene_file.hpp"
#include "core/sweep/grid.hpp"

namespace dampbound::test {

inline SceneSpec shipped_scene(const std::string& name) {
  return load_scene(std::string(DAMPBOUND_SOURCE_DIR) + "/scenes/" + name + ".toml");
}

/// 2 m x 2 kappa x 2 zeta at one dt on `scene`'s stop rules, at most `max_iter` iterations.
inline SweepSpec small_sweep(const SceneSpec& scene, int max_iter = 200,
                             DampingPolicy policy = DampingPolicy::fixed) {
  SweepSpec s;
  s.m = parse_axis("--m", "0.001,0.002", AxisDomain::positive);
  s.kappa = parse_axis("--kappa", "0.001,0.004", AxisDomain::positive);
  s.gamma_mode = GammaMode::zeta;
  s.gamma = parse_axis("--zeta", "0.5,1", AxisDomain::non_negative);
  s.dt = parse_axis("--dt", "0.05", AxisDomain::positive);
  s.factor = parse_axis("--factor", "1", AxisDomain::non_negative);
  s.policy = policy;
  s.rules = scene.rules;
  s.rules.max_iterations = max_iter;
  return s;
}

}  // namespace dampbound::test
