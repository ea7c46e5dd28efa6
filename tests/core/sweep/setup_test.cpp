// What a sweep settles before its first trial: the shard, its identity, its definition, and
// the rows of its CSV.
#include "core/sweep/setup.hpp"

#include <gtest/gtest.h>

#include <set>

#include "core/sweep/trials.hpp"
#include "dampbound/physics/error.hpp"
#include "tests/core/sweep/sweep_test_util.hpp"

namespace dampbound {
namespace {

TEST(SweepSetup, ParseShardAcceptsKOfN) {
  int k = 0, n = 0;
  parse_shard("1/1", k, n);
  EXPECT_EQ(k, 1);
  EXPECT_EQ(n, 1);
  parse_shard("3/7", k, n);
  EXPECT_EQ(k, 3);
  EXPECT_EQ(n, 7);
  parse_shard("999999999/999999999", k, n);
  EXPECT_EQ(k, 999999999);
}

TEST(SweepSetup, ParseShardRefusesEverythingElse) {
  for (const char* bad : {"", "1", "0/1", "2/1", "1/0", "-1/2", "1/2x", "a/b", "1/3/4",
                          "3/99999999999", "1 /2x"}) {
    int k = 5, n = 5;
    SCOPED_TRACE(bad);
    try {
      parse_shard(bad, k, n);
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("--shard"), std::string::npos) << e.what();
    }
    EXPECT_EQ(k, 5);  // left as it was
    EXPECT_EQ(n, 5);
  }
}

TEST(SweepSetup, DefinitionAndIdentity) {
  const SceneSpec scene = test::shipped_scene("two-node");
  SweepSpec s = test::small_sweep(scene, 300);
  s.rules.rule = StopRule::first_entry;  // the paper's sweeps keep their definition and id
  const std::string d = sweep_definition(s);
  EXPECT_EQ(d.rfind("m=0.001,0.002 kappa=0.001,0.004 zeta=0.5,1 dt=0.05 policy=fixed factor=1 "
                    "max-iter=300 ",
                    0),
            0u)
      << d;
  EXPECT_EQ(d.find("rule=settled"), std::string::npos);
  s.rules.rule = StopRule::settled;
  const std::string ds = sweep_definition(s);
  EXPECT_EQ(ds, d + " rule=settled");
  const std::string id = sweep_id("scene bytes", d);
  EXPECT_EQ(id.size(), 16u);
  EXPECT_EQ(id.find_first_not_of("0123456789abcdef"), std::string::npos);
  EXPECT_EQ(id, sweep_id("scene bytes", d));
  EXPECT_NE(id, sweep_id("scene bytes.", d));
  EXPECT_NE(id, sweep_id("scene bytes", ds));
}

TEST(SweepSetup, RowsOfTheShardsPartitionTheGrid) {
  const SceneSpec scene = test::shipped_scene("two-node");
  const SweepSpec s = test::small_sweep(scene);
  const SweepGrid grid(s);
  const TrialClasses classes = find_classes(grid, similarity_unavailable(scene));
  std::vector<TrialResult> results(classes.count());
  for (size_t c = 0; c < results.size(); ++c) {
    results[c].outcome = Outcome::restored;
    results[c].iterations = static_cast<int>(c) + 10;
  }
  const auto all = sweep_rows(grid, classes, results, 1, 1);
  ASSERT_EQ(all.size(), grid.trials());
  for (size_t t = 0; t < all.size(); ++t) {
    const TrialParams p = grid.params(t);
    EXPECT_EQ(all[t].trial, t);
    EXPECT_EQ(all[t].m, p.m);
    EXPECT_EQ(all[t].kappa, p.kappa);
    EXPECT_EQ(all[t].gamma, p.gamma);
    EXPECT_EQ(all[t].zeta, grid.zeta(t));
    EXPECT_EQ(all[t].iterations, static_cast<int>(classes.class_of[t]) + 10);
  }
  std::set<std::uint64_t> seen;
  for (int shard = 1; shard <= 3; ++shard)
    for (const SweepRow& r : sweep_rows(grid, classes, results, shard, 3)) {
      EXPECT_EQ(static_cast<int>(classes.class_of[r.trial] % 3), shard - 1);
      EXPECT_TRUE(seen.insert(r.trial).second);
    }
  EXPECT_EQ(seen.size(), grid.trials());
}

TEST(SweepSetup, ResourcesOfASmallGridFit) {
  const SceneSpec scene = test::shipped_scene("two-node");
  const SweepGrid grid(test::small_sweep(scene));
  EXPECT_NO_THROW(check_sweep_resources(grid, ::testing::TempDir() + "x.csv", 1));
}

}  // namespace
}  // namespace dampbound
