#include "core/analysis/worst_nodes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>

#include "core/physics/safe_bound_nodes.hpp"

namespace dampbound {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  const size_t h = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(h), v.end());
  return v[h];
}

std::string times(const char* what, double r, const char* how) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%s %.2gx %s the median", what, r, how);
  return buf;
}

/// The medians the causes are told against, and each node described against them.
struct Describer {
  const Model& model;
  std::vector<double> dts, gammas, edges;
  std::vector<int> free;
  double median_mass = 0, median_kappa = 0, median_edge = 0, median_degree = 0;

  Describer(const Model& m, const std::vector<Vec3>& x, double dt) : model(m) {
    safe_bounds_per_node(model, x, dt, dts, gammas);
    std::vector<double> masses;
    for (int i = 0; i < model.spec().node_count(); ++i)
      if (!model.spec().fixed[static_cast<size_t>(i)]) {
        free.push_back(i);
        masses.push_back(model.mass[static_cast<size_t>(i)]);
      }
    for (const Spring& s : model.spec().springs)
      edges.push_back((model.spec().rest[static_cast<size_t>(s.j)] - model.spec().rest[static_cast<size_t>(s.i)]).norm());
    median_mass = median(masses);
    median_kappa = median(model.spring_kappa);
    median_edge = median(edges);
    std::vector<double> degrees;
    for (int i : free)
      degrees.push_back(model.incident_offset[static_cast<size_t>(i) + 1] -
                        model.incident_offset[static_cast<size_t>(i)]);
    median_degree = median(degrees);
  }

  WorstNode operator()(int i) const {
    const size_t u = static_cast<size_t>(i);
    WorstNode d;
    d.node = i;
    d.dt_safe = dts[u];
    d.gamma_safe = gammas[u];
    d.mass = model.mass[u];
    d.stiffest = model.node_kappa[u];
    d.shortest_edge = std::numeric_limits<double>::infinity();
    for (int k = model.incident_offset[u]; k < model.incident_offset[u + 1]; ++k) {
      const int s = model.incident[static_cast<size_t>(k)];
      d.shortest_edge = std::min(d.shortest_edge, edges[static_cast<size_t>(s >= 0 ? s : ~s)]);
      ++d.degree;
    }
    // The cause: the largest of the three ratios against the medians (1 = typical).
    const double r_edge = d.shortest_edge > 0 ? median_edge / d.shortest_edge : 0;
    const double r_mass = d.mass > 0 ? median_mass / d.mass : 0;
    const double r_kappa = median_kappa > 0 ? d.stiffest / median_kappa : 0;
    const double r_degree = median_degree > 0 ? d.degree / median_degree : 0;
    const double top = std::max({r_edge, r_mass, r_kappa, r_degree});
    if (top < 1.5)
      d.cause = "typical node (mass, stiffness, edges and degree within 1.5x of the median)";
    else if (top == r_edge)
      d.cause = times("edge", r_edge, "shorter than");
    else if (top == r_degree)
      d.cause = times("degree", r_degree, "above");
    else if (top == r_mass)
      d.cause = times("mass", r_mass, "below");
    else
      d.cause = times("spring", r_kappa, "stiffer than");
    return d;
  }
};

}  // namespace

WorstNodes worst_nodes(const Model& model, const std::vector<Vec3>& x, double dt, int count) {
  WorstNodes w;
  const Describer describe(model, x, dt);
  w.median_mass = describe.median_mass;
  w.median_kappa = describe.median_kappa;
  w.median_edge = describe.median_edge;
  auto pick = [&](const std::vector<double>& key, std::vector<WorstNode>& out) {
    std::vector<int> order = describe.free;
    const size_t k = std::min(order.size(), static_cast<size_t>(std::max(count, 0)));
    std::partial_sort(order.begin(), order.begin() + static_cast<long>(k), order.end(),
                      [&](int a, int b) {
                        const double ka = key[static_cast<size_t>(a)], kb = key[static_cast<size_t>(b)];
                        return ka < kb || (ka == kb && a < b);
                      });
    for (size_t j = 0; j < k; ++j) out.push_back(describe(order[j]));
  };
  pick(describe.dts, w.by_dt);
  pick(describe.gammas, w.by_gamma);
  return w;
}

std::vector<WorstNode> describe_nodes(const Model& model, const std::vector<Vec3>& x, double dt,
                                      const std::vector<int>& nodes) {
  const Describer describe(model, x, dt);
  std::vector<WorstNode> out;
  for (int i : nodes) out.push_back(describe(i));
  return out;
}

}  // namespace dampbound
