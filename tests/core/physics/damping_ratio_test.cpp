// The nodal damping ratio (SPEC 10): zeta_i = gamma_i / (2 sqrt(m_i kappa_i)), in and out.
#include "core/physics/damping_ratio.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "dampbound/physics/error.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound {
namespace {

/// Three free nodes on a line: a light node 0, a stiff spring 1-2, node 2 also anchored.
ModelSpec uneven() {
  ModelSpec s;
  for (int k = 0; k < 4; ++k) add_node(s, Vec3(k, 0, 0));
  s.mass_scale[0] = 0.25;
  add_spring(s, 0, 1, 1);
  add_spring(s, 1, 2, 9);
  s.anchor_scale[2] = 4;
  return s;  // node 3: no spring, no anchor
}

TEST(DampingRatio, ResolvedZetaGivesEachNodeItsOwnLowerBoundTimesZeta) {
  ModelSpec spec = uneven();
  Params p;
  p.m = 0.002;
  p.kappa = 0.003;
  p.zeta = 0.7;
  resolve_zeta(spec, p);
  EXPECT_FALSE(p.zeta.has_value());
  const Model m = compile_model(spec, p);
  // gamma_i = zeta * 2 sqrt(m_i kappa_i), kappa_i the stiffest spring or anchor (SPEC 3).
  const double kappa_i[] = {1 * 0.003, 9 * 0.003, 9 * 0.003, 0};
  for (int i = 0; i < 4; ++i) {
    const double want = 0.7 * 2 * std::sqrt(p.m * spec.mass_scale[static_cast<size_t>(i)] * kappa_i[i]);
    EXPECT_NEAR(m.gamma[static_cast<size_t>(i)], want, 1e-15) << "node " << i;
  }
  const std::vector<double> zeta = damping_ratio(m);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(zeta[static_cast<size_t>(i)], 0.7, 1e-12);
  EXPECT_TRUE(std::isnan(zeta[3]));  // no spring, no anchor: no ratio
  const DampingRatioRange r = damping_ratio_range(m);
  EXPECT_NEAR(r.min, 0.7, 1e-12);
  EXPECT_NEAR(r.max, 0.7, 1e-12);
}

TEST(DampingRatio, GammaGivesAVaryingRatio) {
  Params p;  // gamma = 0.002 at m = kappa = 0.001: zeta 1 where kappa_i = kappa and m_i = m
  const Model m = compile_model(uneven(), p);
  const DampingRatioRange r = damping_ratio_range(m);
  EXPECT_NEAR(r.max, 2.0, 1e-12);      // node 0: m_i = m/4
  EXPECT_NEAR(r.min, 1.0 / 3, 1e-12);  // nodes 1, 2: kappa_i = 9 kappa
  EXPECT_FALSE(r.uniform());
}

TEST(DampingRatio, WithoutZetaNothingChangesAndResolvingTwiceIsResolvingOnce) {
  ModelSpec spec = uneven();
  Params p;
  resolve_zeta(spec, p);
  EXPECT_EQ(spec.gamma_scale, uneven().gamma_scale);
  EXPECT_EQ(p.gamma, Params{}.gamma);
  p.zeta = 1;
  resolve_zeta(spec, p);
  const std::vector<double> once = spec.gamma_scale;
  resolve_zeta(spec, p);  // zeta was cleared: no second scaling
  EXPECT_EQ(spec.gamma_scale, once);
}

TEST(DampingRatio, SceneRunsMustGiveTheDampingTheSameWay) {
  SceneSpec s;
  s.model = uneven();
  s.params.zeta = 1;
  RunSpec run{"a", s.params, s.rules};
  run.params.zeta = 2;
  run.params.m = 0.004;
  s.runs.push_back(run);
  SceneSpec ok = s;
  resolve_zeta(ok);
  EXPECT_NEAR(ok.runs[0].params.gamma, 2 * 2 * std::sqrt(0.004 * 0.001), 1e-15);
  s.runs[0].params.zeta.reset();
  EXPECT_THROW(resolve_zeta(s), InputError);
}

}  // namespace
}  // namespace dampbound
