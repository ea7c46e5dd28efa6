// Tests of core/analysis/perturbation_growth: the check by simulation that the exact
// analysis is set against (its uses in linear_stability_*_test.cpp and verdicts_random_test.cpp
// check decay and growth against the limits); here its edges.
#include "core/analysis/perturbation_growth.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "core/analysis/linear_stability_exact.hpp"

namespace dampbound {
namespace {

/// Nodes 0 (fixed) - 1 - 2 on two springs.
ModelSpec chain() {
  ModelSpec spec;
  for (int k = 0; k < 3; ++k) add_node(spec, Vec3(k, 0, 0));
  add_spring(spec, 0, 1);
  add_spring(spec, 1, 2);
  spec.fixed[0] = 1;
  return spec;
}

// A run that grows until its positions overflow (inf, then NaN) has grown: its growth is inf,
// not the 0 that max() over NaN distances gave (seen under clang + ASan, where a chain like
// this one reached NaN within 2000 steps past its dt limit).
TEST(PerturbationGrowth, ARunThatOverflowsHasGrown) {
  const ModelSpec spec = chain();
  Params p;
  p.dt = 10 * exact_stability(compile_model(spec, p), spec.rest, p).dt_max;
  const Model m = compile_model(spec, p);
  EXPECT_TRUE(std::isinf(perturbation_growth(m, p, 20000)));
  EXPECT_TRUE(std::isinf(perturbation_growth(m, m.spec().rest, p, 20000)));
}

// About the rest state the two forms are one; positions must be one per node.
TEST(PerturbationGrowth, AboutRestIsTheRestForm) {
  Params p;
  const Model m = compile_model(chain(), p);
  EXPECT_EQ(perturbation_growth(m, p, 300), perturbation_growth(m, m.spec().rest, p, 300));
  EXPECT_LT(perturbation_growth(m, p, 300), 1.0);
  EXPECT_THROW(perturbation_growth(m, {Vec3::Zero()}, p, 10), std::invalid_argument);
}

}  // namespace
}  // namespace dampbound
