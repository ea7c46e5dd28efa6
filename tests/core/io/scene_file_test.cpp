// Scene files (core/io/scene_file.hpp): the shipped scenes, runs and expectations, and every
// bad-input case naming file and line.
#include "core/io/scene_file.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "dampbound/physics/error.hpp"
#include "tests/core/test_util.hpp"

namespace dampbound {
namespace {

TEST(PaperPlane, CountsAndPerturbation) {
  const SceneSpec s = load_scene(test::source_path("scenes/paper-plane.toml"));
  EXPECT_EQ(s.model.node_count(), 1296);
  EXPECT_EQ(s.model.spring_count(), 3745);
  EXPECT_EQ(s.model.anchor_count(), 1296);
  ASSERT_EQ(s.perturbations.size(), 1u);
  EXPECT_EQ(s.perturbations[0].node, 18 * 36 + 18);
  EXPECT_EQ(s.perturbations[0].displacement, Vec3(0, 5, 0));
  EXPECT_EQ(s.watched, 666);
  EXPECT_DOUBLE_EQ(s.rules.reference, 5.0);
  EXPECT_EQ(s.rules.max_iterations, 1000);
  EXPECT_DOUBLE_EQ(s.params.dt, 0.05);
  // Node (a, b) at (a h, 0, b h).
  EXPECT_TRUE(s.model.rest[35 * 36 + 2].isApprox(Vec3(35 * 0.57, 0, 2 * 0.57)));
  // Rest lengths equal initial lengths: h for edges, h sqrt 2 for diagonals.
  for (const Spring& sp : s.model.springs) {
    const double l = (s.model.rest[sp.j] - s.model.rest[sp.i]).norm();
    EXPECT_DOUBLE_EQ(sp.rest_length, l);
    EXPECT_TRUE(std::abs(l - 0.57) < 1e-12 || std::abs(l - 0.57 * std::sqrt(2.0)) < 1e-12);
  }
  const State st = initial_state(s);
  EXPECT_DOUBLE_EQ(st.x[666].y(), 5.0);
  EXPECT_DOUBLE_EQ(st.x[665].y(), 0.0);
}

TEST(TwoNode, Shape) {
  const SceneSpec s = load_scene(test::source_path("scenes/two-node.toml"));
  EXPECT_EQ(s.model.node_count(), 2);
  EXPECT_EQ(s.model.spring_count(), 1);
  EXPECT_EQ(s.model.anchor_count(), 0);
  EXPECT_TRUE(s.model.fixed[0]);
  EXPECT_FALSE(s.model.fixed[1]);
  EXPECT_EQ(s.watched, 1);
  EXPECT_DOUBLE_EQ(s.rules.reference, 0.5);
}

/// Parses `text` and returns the InputError message ("" if it parsed).
std::string error_of(const std::string& text) {
  return test::input_error([&] { parse_scene(text, "bad.toml"); });
}

const char* kGrid = "[grid]\nnx = 4\nnz = 4\nspacing = 1.0\n";

TEST(BadScene, UnknownKeyNamesLine) {
  EXPECT_EQ(error_of(std::string(kGrid) + "[params]\nm = 1\nmass = 2\n"),
            "bad.toml:7: unknown key 'mass' in [params]");
  EXPECT_EQ(error_of("colour = 1\n" + std::string(kGrid)),
            "bad.toml:1: unknown key 'colour' in the scene");
}

TEST(BadScene, MissingValue) {
  EXPECT_EQ(error_of("[grid]\nnx = 4\nspacing = 1.0\n"), "bad.toml:1: missing 'nz' in [grid]");
  EXPECT_NE(error_of("[grid]\nnx = 4\nnz =\n").find("bad.toml:3:"), std::string::npos);
  EXPECT_EQ(error_of("name = \"empty\"\n"),
            "bad.toml:1: the scene has no geometry: add [grid], [[node]] entries or [mesh]");
}

TEST(BadScene, NegativeMass) {
  EXPECT_EQ(error_of(std::string(kGrid) + "[params]\nm = -0.001\n"),
            "bad.toml:6: m must be > 0");
  EXPECT_EQ(error_of("[[node]]\nx = [0, 0, 0]\nmass_scale = -1\n"),
            "bad.toml:3: mass_scale must be > 0");
}

TEST(BadScene, NaNAndInfinity) {
  EXPECT_EQ(error_of(std::string(kGrid) + "[params]\nkappa = nan\n"),
            "bad.toml:6: kappa must be finite (got nan)");
  EXPECT_NE(error_of("[[node]]\nx = [0, inf, 0]\n").find("bad.toml:2: x must be finite"),
            std::string::npos);
}

TEST(BadScene, SpringToMissingNode) {
  EXPECT_EQ(error_of("[[node]]\nx = [0, 0, 0]\n[[node]]\nx = [1, 0, 0]\n[[spring]]\n"
                     "nodes = [0, 5]\n"),
            "bad.toml:6: spring node 5 does not exist (the scene has 2 nodes)");
}

TEST(BadScene, DuplicateSpring) {
  EXPECT_EQ(error_of("[[node]]\nx = [0, 0, 0]\n[[node]]\nx = [1, 0, 0]\n[[spring]]\n"
                     "nodes = [0, 1]\n[[spring]]\nnodes = [1, 0]\n"),
            "bad.toml:8: duplicate spring 1-0");
}

TEST(BadScene, SyntaxErrorNamesLine) {
  EXPECT_NE(error_of("[grid]\nnx = 4\nnz = = 4\n").rfind("bad.toml:3: ", 0), std::string::npos);
}

TEST(BadScene, OutOfGridReferences) {
  EXPECT_EQ(error_of(std::string(kGrid) + "[[perturb]]\nnode = [4, 0]\n"),
            "bad.toml:6: perturb node [4, 0] is outside the 4 x 4 grid");
  EXPECT_EQ(error_of("watch = 16\n" + std::string(kGrid)),
            "bad.toml:1: watch 16 does not exist (the scene has 16 nodes)");
}

TEST(BadScene, WrongTypesAndPolicy) {
  EXPECT_EQ(error_of(std::string(kGrid) + "[params]\npolicy = \"max\"\n"),
            "bad.toml:6: policy must be one of fixed, clamp, upper, lower or safe");
  EXPECT_EQ(error_of(std::string(kGrid) + "[params]\ndt = \"fast\"\n"),
            "bad.toml:6: dt must be a number");
  EXPECT_EQ(error_of(std::string(kGrid) + "[protocol]\nmax_iterations = 0\n"),
            "bad.toml:6: max_iterations must be in 1..100000000");
}

TEST(BadScene, MissingFile) {
  EXPECT_THROW(load_scene("/nonexistent/scene.toml"), InputError);
}

TEST(Scene, RunsAndExpectations) {
  const SceneSpec s = parse_scene(std::string(kGrid) + R"(
[[run]]
label = "soft"
gamma = 0.0005
max_iterations = 50
[[expect]]
run = "soft"
rule = "first-entry"
outcome = "restored"
iterations = [1, 40]
)",
                                  "x.toml");
  ASSERT_EQ(s.runs.size(), 1u);
  EXPECT_EQ(s.runs[0].params.gamma, 0.0005);
  EXPECT_EQ(s.runs[0].rules.max_iterations, 50);
  ASSERT_EQ(s.expectations.size(), 1u);
  EXPECT_EQ(*s.expectations[0].outcome, Outcome::restored);
  EXPECT_EQ(*s.expectations[0].iterations_max, 40);
  EXPECT_EQ(error_of(std::string(kGrid) + "[[expect]]\nrun = \"nope\"\n"),
            "bad.toml:6: expect refers to run 'nope', which is not declared");
}

TEST(ResolveScene, ANameIsLookedUpAmongTheScenesAPathIsNot) {
  const std::string dir = test::source_path("scenes");
  EXPECT_EQ(resolve_scene("two-node", dir), dir + "/two-node.toml");
  EXPECT_EQ(resolve_scene("two-node.toml", dir), dir + "/two-node.toml");
  EXPECT_EQ(resolve_scene("./two-node", dir), "./two-node");  // a path: as typed
  EXPECT_EQ(resolve_scene("no-such-scene", dir), "no-such-scene");
  EXPECT_EQ(resolve_scene("two-node", ""), "two-node");  // no scene folder
  EXPECT_EQ(load_scene(resolve_scene("two-node", dir)).model.node_count(), 2);
}

}  // namespace
}  // namespace dampbound
