// The monitor over a user's arrays: every bound and check is core's own function (bounds.cpp,
// forces.cpp, linear_stability*.cpp) applied to a Model that holds the user's topology.
#include "dampbound/monitor.hpp"

#include <cmath>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>

#include "core/analysis/linear_stability_exact.hpp"
#include "core/physics/safe_bound.hpp"
#include "dampbound/analysis/linear_stability.hpp"
#include "dampbound/physics/forces.hpp"

namespace dampbound {

namespace {

/// Unit parameters: with m = kappa = gamma = 1, compile_model() turns the scales (the user's
/// m_i, kappa_ij, kappa_a,i, gamma_i) into the values themselves, exactly.
Params unit_params(double dt) {
  Params p;
  p.m = 1;
  p.kappa = 1;
  p.gamma = 1;
  p.dt = dt;
  return p;
}

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("monitor: " + what);
}

// gamma_i: finite (require_finite's words) and >= 0.
void require_damping(NodeScalars gamma) {
  require_finite(gamma, "gamma");
  for (Eigen::Index i = 0; i < gamma.size(); ++i)
    require(gamma[i] >= 0, "gamma[" + std::to_string(i) + "] must be >= 0 (node " +
                               std::to_string(i) + ")");
}

// dt, factor and the like: number_problem's rule and words, as the CLI's flags.
void require_number(double x, const char* name, bool allow_zero) {
  if (const auto why = number_problem(x, allow_zero)) require(false, std::string(name) + " " + *why);
}

}  // namespace

void require_finite(NodeVectors a, const char* what) {
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    if (!a.row(i).allFinite())
      throw std::invalid_argument(std::string(what) + "[" + std::to_string(i) +
                                  "] is not finite (node " + std::to_string(i) + ")");
}

void require_finite(NodeScalars a, const char* what) {
  for (Eigen::Index i = 0; i < a.size(); ++i)
    if (!std::isfinite(a[i]))
      throw std::invalid_argument(std::string(what) + "[" + std::to_string(i) +
                                  "] is not finite (node " + std::to_string(i) + ")");
}

Monitor::Monitor(NodeScalars mass, SpringPairs springs, NodeScalars stiffness,
                 NodeScalars rest_length) {
  const Eigen::Index n = mass.size();
  require(n > 0, "mass must have at least one node");
  require(n <= std::numeric_limits<int>::max() / 2, "too many nodes");
  ModelSpec spec;
  require(stiffness.size() == springs.rows() && rest_length.size() == springs.rows(),
          "springs, stiffness and rest_length must have the same length");
  for (Eigen::Index i = 0; i < n; ++i) {
    require(std::isfinite(mass[i]) && mass[i] > 0,
            "mass[" + std::to_string(i) + "] must be finite and > 0");
    add_node(spec, Vec3::Zero());
    spec.mass_scale.back() = mass[i];
    spec.gamma_scale.back() = 0;
  }
  for (Eigen::Index s = 0; s < springs.rows(); ++s) {
    const int i = springs(s, 0), j = springs(s, 1);
    const std::string at = "spring " + std::to_string(s);
    require(i >= 0 && j >= 0 && i < n && j < n && i != j,
            at + ": nodes must be two different indices in 0.." + std::to_string(n - 1));
    require(std::isfinite(stiffness[s]) && stiffness[s] > 0, at + ": stiffness must be > 0");
    require(std::isfinite(rest_length[s]) && rest_length[s] >= 0,
            at + ": rest_length must be >= 0");
    Spring sp;
    sp.i = i;
    sp.j = j;
    sp.rest_length = rest_length[s];
    sp.kappa_scale = stiffness[s];
    spec.springs.push_back(sp);
  }
  model_ = compile_model(std::move(spec), unit_params(1.0));
}

void Monitor::check_size(Eigen::Index n, const char* what) const {
  require(n == node_count(), std::string(what) + " has " + std::to_string(n) +
                                 " rows, the monitor " + std::to_string(node_count()) + " nodes");
}

void Monitor::set_anchors(NodeScalars anchor_stiffness, NodeVectors rest) {
  check_size(anchor_stiffness.size(), "anchor_stiffness");
  check_size(rest.rows(), "rest");
  require_finite(rest, "rest");
  ModelSpec spec = model_;
  for (int i = 0; i < node_count(); ++i) {
    require(std::isfinite(anchor_stiffness[i]) && anchor_stiffness[i] >= 0,
            "anchor_stiffness[" + std::to_string(i) + "] must be >= 0");
    spec.anchor_scale[static_cast<size_t>(i)] = anchor_stiffness[i];
    spec.rest[static_cast<size_t>(i)] = rest.row(i).transpose();
  }
  model_ = compile_model(std::move(spec), unit_params(1.0));
}

void Monitor::set_fixed(const std::uint8_t* fixed, Eigen::Index n) {
  check_size(n, "fixed");
  ModelSpec spec = model_;
  for (Eigen::Index i = 0; i < n; ++i) spec.fixed[static_cast<size_t>(i)] = fixed[i] != 0;
  model_ = compile_model(std::move(spec), unit_params(1.0));
}

void Monitor::set_threads(int threads) {
  std::lock_guard<std::mutex> lock(workers_.mutex);
  workers_.pass.threads.set_threads(threads);
}

int Monitor::threads() const {
  std::lock_guard<std::mutex> lock(workers_.mutex);
  return workers_.pass.threads.threads();
}

void Monitor::lower_bounds(NodeScalarsOut out) const {
  check_size(out.size(), "lower bound output");
  for (int i = 0; i < node_count(); ++i) out[i] = model_.lower_bound[static_cast<size_t>(i)];
}

void Monitor::upper_bounds(NodeVectors v, NodeVectors force, double dt, NodeScalarsOut out) const {
  check_size(v.rows(), "v");
  check_size(force.rows(), "force");
  check_size(out.size(), "upper bound output");
  require_number(dt, "dt", false);
  require_finite(v, "v");
  require_finite(force, "force");
  std::lock_guard<std::mutex> lock(workers_.mutex);
  workers_.pass.threads.run(model_.spec().rest.size(), [&](int, size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) {
      const auto i = static_cast<Eigen::Index>(k);
      out[i] = upper_bound(v.row(i).transpose(), force.row(i).transpose(), model_.mass[k], dt);
    }
  });
}

MonitorReport Monitor::check(NodeVectors v, NodeVectors force, NodeScalars gamma, double dt,
                             DampingPolicy policy, double factor, NodeScalarsOut* gamma_eff,
                             NodeScalarsOut* upper, NodeStatus* status) const {
  require(policy != DampingPolicy::safe,
          "the safe policy needs the positions: call check(x, v, force, gamma, dt, ...)");
  return check_with(nullptr, v, force, gamma, dt, policy, factor, gamma_eff, upper, status);
}

MonitorReport Monitor::check(NodeVectors x, NodeVectors v, NodeVectors force, NodeScalars gamma,
                             double dt, DampingPolicy policy, double factor,
                             NodeScalarsOut* gamma_eff, NodeScalarsOut* upper,
                             NodeStatus* status) const {
  std::vector<double> safe(static_cast<size_t>(node_count()));
  const int compressed = safe_bounds(x, dt, node_scalars_out(safe.data(), node_count()));
  MonitorReport r = check_with(&safe, v, force, gamma, dt, policy, factor, gamma_eff, upper, status);
  r.compressed_springs = compressed;
  return r;
}

int Monitor::safe_bounds(NodeVectors x, double dt, NodeScalarsOut out) const {
  check_size(x.rows(), "x");
  check_size(out.size(), "safe bound output");
  require_number(dt, "dt", false);
  require_finite(x, "x");
  std::lock_guard<std::mutex> lock(workers_.mutex);
  std::vector<double>& row_sum = workers_.row_sum;
  const int compressed =
      safe_row_sums(model_, positions(x), row_sum, &workers_.pass);
  workers_.pass.threads.run(row_sum.size(), [&](int, size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k)
      out[static_cast<Eigen::Index>(k)] =
          model_.spec().fixed[k] ? HUGE_VAL : safe_gamma(model_.mass[k], dt, row_sum[k]);
  });
  return compressed;
}

// The bounds and policy of step() (core/physics/step.cpp) node by node; `safe` is gamma_safe_i or null.
MonitorReport Monitor::check_with(const std::vector<double>* safe, NodeVectors v,
                                  NodeVectors force, NodeScalars gamma, double dt,
                                  DampingPolicy policy, double factor, NodeScalarsOut* gamma_eff,
                                  NodeScalarsOut* upper, NodeStatus* status) const {
  check_size(v.rows(), "v");
  check_size(force.rows(), "force");
  check_size(gamma.size(), "gamma");
  if (gamma_eff) check_size(gamma_eff->size(), "gamma_eff");
  if (upper) check_size(upper->size(), "upper");
  require_number(dt, "dt", false);
  require_number(factor, "factor", true);
  require_finite(v, "v");
  require_finite(force, "force");
  require_damping(gamma);
  // Contiguous ranges of nodes on threads, each with its own report; combined in range order,
  // so the counts and the first indices are those of one loop.
  std::lock_guard<std::mutex> lock(workers_.mutex);
  NodeThreads& threads = workers_.pass.threads;
  std::vector<MonitorReport> parts(static_cast<size_t>(threads.chunks(model_.spec().rest.size())));
  threads.run(model_.spec().rest.size(), [&](int chunk, size_t begin, size_t end) {
    MonitorReport part;  // counted here, stored once: the parts share cache lines
    check_range(safe, v, force, gamma, dt, policy, factor, gamma_eff, upper, status,
                static_cast<int>(begin), static_cast<int>(end), part);
    parts[static_cast<size_t>(chunk)] = part;
  });
  MonitorReport r;
  for (const MonitorReport& p : parts) {
    if (r.first_violating < 0) r.first_violating = p.first_violating;
    if (r.first_unstabilisable < 0) r.first_unstabilisable = p.first_unstabilisable;
    r.violating += p.violating;
    r.unstabilisable += p.unstabilisable;
    r.clamped += p.clamped;
    r.unguaranteed += p.unguaranteed;
  }
  return r;
}

void Monitor::check_range(const std::vector<double>* safe, NodeVectors v, NodeVectors force,
                          NodeScalars gamma, double dt, DampingPolicy policy, double factor,
                          NodeScalarsOut* gamma_eff, NodeScalarsOut* upper, NodeStatus* status,
                          int begin, int end, MonitorReport& r) const {
  for (int i = begin; i < end; ++i) {
    const size_t k = static_cast<size_t>(i);
    if (model_.spec().fixed[k]) {
      if (gamma_eff) (*gamma_eff)[i] = gamma[i];
      if (upper) (*upper)[i] = HUGE_VAL;
      if (status) status[i] = NodeStatus::fixed;
      continue;
    }
    const double lo = model_.lower_bound[k];
    const double hi =
        upper_bound(v.row(i).transpose(), force.row(i).transpose(), model_.mass[k], dt);
    const DampingChoice c =
        safe ? effective_damping(policy, gamma[i], lo, hi, factor, (*safe)[k])
             : effective_damping(policy, gamma[i], lo, hi, factor);
    if (c.unstabilisable && r.unstabilisable++ == 0) r.first_unstabilisable = i;
    if (c.violating && r.violating++ == 0) r.first_violating = i;
    r.clamped += c.status == NodeStatus::clamped;
    r.unguaranteed += c.unguaranteed;
    if (gamma_eff) (*gamma_eff)[i] = c.gamma;
    if (upper) (*upper)[i] = hi;
    if (status) status[i] = c.status;
  }
}

const std::vector<Vec3>& Monitor::positions(NodeVectors x) const {
  check_size(x.rows(), "x");
  std::vector<Vec3>& xs = workers_.x;  // kept between calls: no fresh pages every step
  xs.resize(static_cast<size_t>(node_count()));
  workers_.pass.threads.run(xs.size(), [&](int, size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) xs[k] = x.row(static_cast<Eigen::Index>(k)).transpose();
  });
  return xs;
}

int Monitor::internal_forces(
    NodeVectors x,
    Eigen::Ref<Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>> force) const {
  check_size(force.rows(), "force");
  check_size(x.rows(), "x");
  require_finite(x, "x");
  std::lock_guard<std::mutex> lock(workers_.mutex);
  std::vector<Vec3>& f = workers_.force;
  const int zero_length =
      dampbound::internal_forces(model_, positions(x), f, &workers_.pass);
  workers_.pass.threads.run(f.size(), [&](int, size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) force.row(static_cast<Eigen::Index>(k)) = f[k].transpose();
  });
  return zero_length;
}

MonitorLimits Monitor::exact_limits(NodeVectors x, NodeScalars gamma, double dt,
                                    double max_factor_flops) const {
  check_size(x.rows(), "x");
  check_size(gamma.size(), "gamma");
  require_number(dt, "dt", false);
  require(!std::isnan(max_factor_flops) && max_factor_flops > 0, "max_factor_flops must be > 0");
  require_finite(x, "x");
  require_damping(gamma);
  ModelSpec spec = model_;
  for (int i = 0; i < node_count(); ++i) spec.gamma_scale[static_cast<size_t>(i)] = gamma[i];
  const Params params = unit_params(dt);
  const Model model = compile_model(std::move(spec), params);
  std::vector<Vec3> xs;
  {
    // A copy of its own: the analysis runs for seconds without holding the other calls up.
    std::lock_guard<std::mutex> lock(workers_.mutex);
    xs = positions(x);
  }
  ExactOptions options;
  options.with_radius = false;
  options.max_factor_flops = max_factor_flops;
  const ExactStability e = exact_stability(model, xs, params, options);
  // With params.gamma = 1, exact_stability's interval of the user's gamma is an interval of
  // the factor s that multiplies every gamma_i.
  MonitorLimits l;
  l.lambda_max = e.spectrum.lambda_max;
  l.stable = e.stable;
  l.scale_lo = e.gamma_lo;
  l.scale_hi = e.gamma_hi;
  l.dt_max = e.dt_max;
  if (!e.computed()) {  // over the budget: every number NaN (exact_stability's), and why
    l.not_computed = e.over_budget_reason();
    l.rate_max = l.dt_max_undamped = std::numeric_limits<double>::quiet_NaN();
    l.lambda_max_at_least = e.unfactored.lambda_max_lo;
    l.scale_unstable_from = e.unfactored.gamma_unstable_from;
    l.dt_unstable_from = e.unfactored.dt_unstable_from;
    l.scale_stable_up_to = e.unfactored.gamma_stable_hi;
    l.dt_stable_up_to = e.unfactored.dt_stable_up_to;
    return l;
  }
  l.indefinite = e.indefinite;
  if (e.indefinite) {
    l.rate_max = l.dt_max_undamped = 0;
    return l;
  }
  const LinearLimits uniform = linear_limits(e.spectrum.lambda_max, 1.0, dt);
  l.rate_max = uniform.gamma_max;
  l.dt_max_undamped = uniform.dt_max_undamped;
  return l;
}

}  // namespace dampbound
