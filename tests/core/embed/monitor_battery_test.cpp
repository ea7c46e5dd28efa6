// The monitor's bad-input battery: every call that takes a state, fed NaN and infinities in
// every array at the first and the last node, bad dt, factor and damping, bad topology and
// anchors, and a pool that cannot start its threads. Each case asserts the exception and the
// array and node it names (docs/embedding.md, "Bad input").
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "dampbound/monitor.hpp"
#include "dampbound/physics/error.hpp"
#include "dampbound/physics/node_threads.hpp"
#include "dampbound/run/session.hpp"

namespace dampbound {
namespace {

constexpr int kNodes = 4;
const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

/// A chain of four nodes, three springs, every node anchored, with a state that moves.
struct Chain {
  std::vector<double> mass{1, 2, 1, 3}, stiffness{5, 6, 7}, rest_length{1, 1, 1};
  std::vector<int> pairs{0, 1, 1, 2, 2, 3};
  std::vector<double> anchor{1, 1, 1, 1};
  std::vector<double> rest{0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0};
  std::vector<double> x{0, 0.1, 0, 1.1, 0, 0, 2, 0.2, 0, 3.2, 0, 0};
  std::vector<double> v{1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
  std::vector<double> force{0.1, 0, 0, 0, 0.2, 0, 0, 0, 0.3, 0, 0, 0};
  std::vector<double> gamma{0.5, 0.5, 0.5, 0.5};
  Monitor make() const {
    Monitor m(node_scalars(mass.data(), kNodes), spring_pairs(pairs.data(), 3),
              node_scalars(stiffness.data(), 3), node_scalars(rest_length.data(), 3));
    m.set_anchors(node_scalars(anchor.data(), kNodes), node_vectors(rest.data(), kNodes));
    return m;
  }
};

/// Every call that reads a state, as one function of the chain's arrays and dt, policy, factor.
struct Call {
  const char* name;
  std::function<void(const Monitor&, const Chain&, double dt, DampingPolicy, double factor)> run;
  std::vector<std::string> reads;  ///< the state arrays it takes
};

std::vector<Call> calls() {
  std::vector<Call> c;
  c.push_back({"upper_bounds",
               [](const Monitor& m, const Chain& a, double dt, DampingPolicy, double) {
                 std::vector<double> out(kNodes);
                 m.upper_bounds(node_vectors(a.v.data(), kNodes),
                                node_vectors(a.force.data(), kNodes), dt,
                                node_scalars_out(out.data(), kNodes));
               },
               {"v", "force"}});
  c.push_back({"check",
               [](const Monitor& m, const Chain& a, double dt, DampingPolicy p, double f) {
                 m.check(node_vectors(a.v.data(), kNodes), node_vectors(a.force.data(), kNodes),
                         node_scalars(a.gamma.data(), kNodes), dt,
                         p == DampingPolicy::safe ? DampingPolicy::clamp : p, f);
               },
               {"v", "force", "gamma"}});
  c.push_back({"check_with_x",
               [](const Monitor& m, const Chain& a, double dt, DampingPolicy p, double f) {
                 m.check(node_vectors(a.x.data(), kNodes), node_vectors(a.v.data(), kNodes),
                         node_vectors(a.force.data(), kNodes),
                         node_scalars(a.gamma.data(), kNodes), dt, p, f);
               },
               {"x", "v", "force", "gamma"}});
  c.push_back({"safe_bounds",
               [](const Monitor& m, const Chain& a, double dt, DampingPolicy, double) {
                 std::vector<double> out(kNodes);
                 m.safe_bounds(node_vectors(a.x.data(), kNodes), dt,
                               node_scalars_out(out.data(), kNodes));
               },
               {"x"}});
  c.push_back({"internal_forces",
               [](const Monitor& m, const Chain& a, double, DampingPolicy, double) {
                 Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> f(kNodes, 3);
                 m.internal_forces(node_vectors(a.x.data(), kNodes), f);
               },
               {"x"}});
  c.push_back({"exact_limits",
               [](const Monitor& m, const Chain& a, double dt, DampingPolicy, double) {
                 m.exact_limits(node_vectors(a.x.data(), kNodes),
                                node_scalars(a.gamma.data(), kNodes), dt);
               },
               {"x", "gamma"}});
  return c;
}

std::vector<double>& array_of(Chain& a, const std::string& name) {
  if (name == "x") return a.x;
  if (name == "v") return a.v;
  if (name == "force") return a.force;
  return a.gamma;
}

/// (call, array, node, component, value): a non-finite number where the call reads a state.
struct NonFinite {
  int call;
  std::string array;
  int node;
  int component;
  double value;
};

std::vector<NonFinite> non_finite_cases() {
  std::vector<NonFinite> out;
  const std::vector<Call> cs = calls();
  for (int c = 0; c < static_cast<int>(cs.size()); ++c)
    for (const std::string& a : cs[static_cast<size_t>(c)].reads)
      for (int node : {0, kNodes - 1})
        for (double value : {kNaN, kInf, -kInf})
          out.push_back({c, a, node, a == "gamma" ? 0 : (node == 0 ? 1 : 2), value});
  return out;
}

class MonitorNonFinite : public ::testing::TestWithParam<NonFinite> {};

TEST_P(MonitorNonFinite, IsAnErrorNamingTheArrayAndTheNode) {
  const NonFinite& p = GetParam();
  Chain a;
  const Monitor m = a.make();
  const Call call = calls()[static_cast<size_t>(p.call)];
  call.run(m, a, 0.01, DampingPolicy::safe, 1.0);  // fine as given
  std::vector<double>& arr = array_of(a, p.array);
  arr[static_cast<size_t>(p.array == "gamma" ? p.node : 3 * p.node + p.component)] = p.value;
  try {
    call.run(m, a, 0.01, DampingPolicy::safe, 1.0);
    FAIL() << call.name << " accepted " << p.value << " in " << p.array << "[" << p.node << "]";
  } catch (const std::invalid_argument& e) {
    const std::string want = p.array + "[" + std::to_string(p.node) + "]";
    EXPECT_NE(std::string(e.what()).find(want), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(EveryCallEveryArray, MonitorNonFinite,
                         ::testing::ValuesIn(non_finite_cases()));

/// (call, dt, policy, factor, gamma of node 2): a parameter no call may judge with.
struct BadParam {
  int call;
  double dt;
  DampingPolicy policy;
  double factor;
  double gamma;
  const char* named;
};

std::vector<BadParam> bad_param_cases() {
  std::vector<BadParam> out;
  const std::vector<Call> cs = calls();
  for (int c = 0; c < static_cast<int>(cs.size()); ++c) {
    const std::string name = cs[static_cast<size_t>(c)].name;
    if (name != "internal_forces")
      for (double dt : {0.0, -0.01, kNaN, kInf, -kInf})
        out.push_back({c, dt, DampingPolicy::fixed, 1.0, 0.5, "dt"});
    if (name == "check" || name == "check_with_x") {
      for (double f : {-1.0, kNaN, kInf})
        out.push_back({c, 0.01, DampingPolicy::upper, f, 0.5, "factor"});
      out.push_back({c, 0.01, DampingPolicy::fixed, 1.0, -1.0, "gamma[2]"});
      out.push_back({c, 0.01, DampingPolicy::clamp, 1.0, -1e-300, "gamma[2]"});
    }
    if (name == "exact_limits") out.push_back({c, 0.01, DampingPolicy::fixed, 1.0, -1.0, "gamma[2]"});
  }
  return out;
}

class MonitorBadParameter : public ::testing::TestWithParam<BadParam> {};

TEST_P(MonitorBadParameter, IsAnErrorNamingIt) {
  const BadParam& p = GetParam();
  Chain a;
  a.gamma[2] = p.gamma;
  const Monitor m = a.make();
  const Call call = calls()[static_cast<size_t>(p.call)];
  try {
    call.run(m, a, p.dt, p.policy, p.factor);
    FAIL() << call.name << " accepted dt " << p.dt << ", factor " << p.factor << ", gamma "
           << p.gamma;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(p.named), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(EveryCall, MonitorBadParameter, ::testing::ValuesIn(bad_param_cases()));

TEST(MonitorBattery, NaNRestPositionsAreRefused) {
  Chain a;
  Monitor m = a.make();
  a.rest[7] = kNaN;
  EXPECT_THROW(m.set_anchors(node_scalars(a.anchor.data(), kNodes), node_vectors(a.rest.data(), kNodes)),
               std::invalid_argument);
}

TEST(MonitorBattery, AnEmptyModelIsRefused) {
  const double none[1] = {0};
  const int no_pairs[2] = {0, 0};
  EXPECT_THROW(Monitor(node_scalars(none, 0), spring_pairs(no_pairs, 0), node_scalars(none, 0),
                       node_scalars(none, 0)),
               std::invalid_argument);
}

TEST(MonitorBattery, NonFiniteMassesAndSpringsAreRefused) {
  for (double bad : {kNaN, kInf, 0.0, -1.0}) {
    Chain a;
    a.mass[3] = bad;
    EXPECT_THROW(a.make(), std::invalid_argument) << bad;
    Chain b;
    b.stiffness[1] = bad;
    EXPECT_THROW(b.make(), std::invalid_argument) << bad;
  }
}

TEST(MonitorBattery, AValidStateStillGivesAVerdict) {
  Chain a;
  const Monitor m = a.make();
  const MonitorReport r = m.check(node_vectors(a.x.data(), kNodes), node_vectors(a.v.data(), kNodes),
                                  node_vectors(a.force.data(), kNodes),
                                  node_scalars(a.gamma.data(), kNodes), 0.01, DampingPolicy::safe);
  EXPECT_GE(r.violating, 0);
}

// A process whose address space cannot hold another thread's stack: starting the pool is an
// exception, not a hang or std::terminate. In a child, so the limit stays there.
TEST(MonitorBattery, APoolThatCannotStartItsThreadsThrows) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer reserves more address space than the limit allows";
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
  GTEST_SKIP() << "AddressSanitizer reserves more address space than the limit allows";
#endif
#endif
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    alarm(20);  // a pool that waits forever fails the test by SIGALRM
    NodeThreads threads(8);
    threads.set_grain(1);
    std::vector<char> ballast(1 << 20, 1);  // the allocator's arenas exist before the limit
    rlimit now{};
    getrlimit(RLIMIT_AS, &now);
    // Room for what the process has, not for eight more 8 MiB stacks.
    std::FILE* f = std::fopen("/proc/self/statm", "r");
    unsigned long pages = 0;
    if (!f || std::fscanf(f, "%lu", &pages) != 1) _exit(3);
    std::fclose(f);
    const rlim_t limit = static_cast<rlim_t>(pages) * static_cast<rlim_t>(sysconf(_SC_PAGESIZE)) +
                         (4u << 20);
    rlimit lim{limit, now.rlim_max};
    if (setrlimit(RLIMIT_AS, &lim) != 0) _exit(4);
    try {
      threads.run(64, [&](int, std::size_t, std::size_t) { ballast[0] += 1; });
    } catch (const std::runtime_error& e) {
      _exit(std::string(e.what()).find("could not start") != std::string::npos ? 0 : 5);
    }
    _exit(6);  // the threads started after all
  }
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << "the child died of signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 0);
}

TEST(SessionBattery, AnEmptyOrOversizedPaperPlaneIsRefused) {
  for (int n : {0, -1, 2001}) EXPECT_THROW(paper_plane_scene(n), InputError) << n;
  EXPECT_EQ(paper_plane_scene(1).model.node_count(), 1);
}

TEST(SessionBattery, AnEmptySceneIsRefusedNotCrashed) {
  SceneSpec s = paper_plane_scene(3);
  s.model = ModelSpec{};
  EXPECT_THROW(Session session(s), InputError);
  SceneSpec out_of_range = paper_plane_scene(3);
  out_of_range.perturbations[0].node = 9;
  EXPECT_THROW(Session session(out_of_range), InputError);
}

TEST(SessionBattery, ParametersAndRulesAreValidatedAtConstruction) {
  const SceneSpec s = paper_plane_scene(3);
  auto refused = [&](Params p, StopRules r, const std::string& named) {
    try {
      Session session(s, p, r);
      ADD_FAILURE() << "accepted; wanted " << named;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(named), std::string::npos) << e.what();
    }
  };
  for (double bad : {0.0, -1.0, kNaN, kInf}) {
    Params p = s.params;
    p.m = bad;
    refused(p, s.rules, "m must be");
    p = s.params;
    p.dt = bad;
    refused(p, s.rules, "dt must be");
  }
  Params p = s.params;
  p.gamma = -1;
  refused(p, s.rules, "gamma must be >= 0");
  p = s.params;
  p.factor = kNaN;
  refused(p, s.rules, "factor must be finite");
  StopRules r = s.rules;
  r.max_iterations = -5;
  refused(s.params, r, "max_iterations must be in 1..100000000");
  r = s.rules;
  r.restore_fraction = kNaN;
  refused(s.params, r, "restore_fraction must be finite");
}

TEST(SessionBattery, ValidateSpeaksTheCliWords) {
  EXPECT_EQ(number_problem(-1, false).value_or(""), "must be > 0");
  EXPECT_EQ(number_problem(-1, true).value_or(""), "must be >= 0");
  EXPECT_EQ(number_problem(kNaN, true).value_or(""), "must be finite");
  EXPECT_FALSE(number_problem(0, true));
  Params p;
  p.dt = 0;
  EXPECT_EQ(validate(p).value_or(""), "dt must be > 0");
}

}  // namespace
}  // namespace dampbound
