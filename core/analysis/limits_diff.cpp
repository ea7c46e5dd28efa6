#include "core/analysis/limits_diff.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <ostream>
#include <set>
#include <type_traits>

#include "core/analysis/substeps.hpp"
#include "core/analysis/worst_nodes.hpp"
#include "core/io/format.hpp"
#include "core/io/json_read.hpp"
#include "core/physics/detail/numbers.hpp"
#include "core/physics/integrate.hpp"
#include "core/physics/safe_bound_nodes.hpp"
#include "dampbound/analysis/linear_stability.hpp"
#include "dampbound/physics/error.hpp"
#include "dampbound/physics/stiffness.hpp"

namespace dampbound {

namespace {

/// The index's top eigenvector at step h: per node, the share of its squared norm.
void limiting_mode(const Model& model, double h, LimitsSnapshot& s) {
  const std::vector<Vec3>& x = model.spec().rest;
  const SparseMatrix A = mass_weighted(model, tangent_stiffness(model, x));
  const SparseMatrix C = weighted_damping(model, x, model.gamma);
  Eigen::VectorXd v;
  largest_eigenpair((h * h) * A + (2 * h) * C, v);
  const std::vector<int> block = free_blocks(model);
  std::vector<std::pair<double, int>> share;
  const double total = v.squaredNorm();
  if (!(total > 0)) return;
  for (size_t i = 0; i < block.size(); ++i)
    if (block[i] >= 0) share.push_back({v.segment<3>(3 * block[i]).squaredNorm() / total, int(i)});
  std::sort(share.begin(), share.end(),
            [](const auto& a, const auto& b) { return a.first > b.first || (a.first == b.first && a.second < b.second); });
  double sum = 0;
  for (const auto& [w, i] : share) {
    if (sum >= 0.9 || s.mode_nodes.size() >= 8) break;
    s.mode_nodes.push_back(i);
    s.mode_share.push_back(w);
    sum += w;
  }
}

std::string point(const Vec3& p) {
  return "(" + format_digits(p.x(), 4) + ", " + format_digits(p.y(), 4) + ", " +
         format_digits(p.z(), 4) + ")";
}

std::string ratio_text(double from, double to) {
  if (from == 0) return format_digits(from, 4) + " -> " + format_digits(to, 4);
  return "x" + format_digits(to / from, 3) + " (" + format_digits(from, 4) + " -> " +
         format_digits(to, 4) + ")";
}

/// New node index -> old node index (-1: none) by rest position, within 1e-9 of the size.
std::vector<int> match_nodes(const std::vector<Vec3>& old_rest, const std::vector<Vec3>& new_rest) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto* rest : {&old_rest, &new_rest})
    for (const Vec3& p : *rest) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double size = (hi.array() >= lo.array()).all() ? (hi - lo).norm() : 0.0;
  const double tol = size > 0 ? 1e-9 * size : 1e-300, cell = size > 0 ? 1e-6 * size : 1.0;
  using Key = std::array<long long, 3>;
  const auto key = [&](const Vec3& p) {
    return Key{std::llround(p.x() / cell), std::llround(p.y() / cell), std::llround(p.z() / cell)};
  };
  std::map<Key, std::vector<int>> grid;
  for (size_t i = 0; i < old_rest.size(); ++i) grid[key(old_rest[i])].push_back(int(i));
  std::vector<int> match(new_rest.size(), -1);
  std::vector<char> taken(old_rest.size(), 0);
  for (size_t i = 0; i < new_rest.size(); ++i) {
    const Key k = key(new_rest[i]);
    double best = tol;
    for (long long a = -1; a <= 1; ++a)
      for (long long b = -1; b <= 1; ++b)
        for (long long c = -1; c <= 1; ++c) {
          const auto it = grid.find(Key{k[0] + a, k[1] + b, k[2] + c});
          if (it == grid.end()) continue;
          for (int o : it->second) {
            const double d = (old_rest[size_t(o)] - new_rest[i]).norm();
            if (!taken[size_t(o)] && d <= best) best = d, match[i] = o;
          }
        }
    if (match[i] >= 0) taken[size_t(match[i])] = 1;
  }
  return match;
}

}  // namespace

LimitsSnapshot limits_snapshot(const SceneSpec& scene, const Params& params,
                               const ExactOptions& options) {
  LimitsSnapshot s;
  s.scene = scene.name.empty() ? scene.path : scene.name;
  s.params = params;
  s.params.zeta.reset();
  s.params.policy = DampingPolicy::fixed;
  const Model model = compile_model(scene.model, s.params);
  const std::vector<Vec3>& x = model.spec().rest;
  ExactOptions o = options;
  o.with_radius = false;
  const ExactStability e = exact_stability(model, x, s.params, o);
  s.method = to_string(e.method);
  s.dt_limit = e.computed() ? e.dt_max : kNaN;
  s.gamma_lo = e.computed() ? e.gamma_lo : kNaN;
  s.gamma_hi = e.computed() ? e.gamma_hi : kNaN;
  std::vector<double> gamma_safe;
  safe_bounds_per_node(model, x, s.params.dt, s.node_dt_safe, gamma_safe);
  s.dt_safe = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < x.size(); ++i)
    if (!model.spec().fixed[i] && s.node_dt_safe[i] < s.dt_safe)
      s.dt_safe = s.node_dt_safe[i], s.dt_safe_node = int(i);
  for (const WorstNode& w : worst_nodes(model, x, s.params.dt, 5).by_dt)
    s.worst.push_back({w.node, w.dt_safe, w.cause});
  if (integrator_traits(s.params.integrator).paper_step && std::isfinite(s.dt_limit) &&
      s.dt_limit > 0 && e.computed())
    limiting_mode(model, 0.999 * s.dt_limit, s);
  s.rest = x;
  s.mass = model.mass;
  s.anchor = model.anchor_kappa;
  s.fixed = model.spec().fixed;
  for (size_t k = 0; k < model.spec().springs.size(); ++k) {
    const Spring& sp = model.spec().springs[k];
    s.spring_i.push_back(sp.i);
    s.spring_j.push_back(sp.j);
    s.spring_kappa.push_back(model.spring_kappa[k]);
    s.spring_rest_length.push_back(sp.rest_length);
  }
  return s;
}

int limit_substeps(double frame_dt, double dt_limit) {
  if (std::isinf(dt_limit) && dt_limit > 0) return 1;
  return substeps_below(frame_dt, dt_limit);
}

LimitsDiff diff_limits(const LimitsSnapshot& o, const LimitsSnapshot& n) {
  LimitsDiff d;
  d.drop = 1 - n.dt_limit / o.dt_limit;
  const auto param = [&](const char* name, double a, double b) {
    if (a != b) d.parameters.push_back(std::string(name) + " " + format_digits(a, 6) + " -> " +
                                       format_digits(b, 6));
  };
  param("m", o.params.m, n.params.m);
  param("kappa", o.params.kappa, n.params.kappa);
  param("gamma", o.params.gamma, n.params.gamma);
  param("dt", o.params.dt, n.params.dt);
  param("kd", o.params.kd, n.params.kd);
  param("rayleigh_mass", o.params.rayleigh_mass, n.params.rayleigh_mass);
  param("rayleigh_stiffness", o.params.rayleigh_stiffness, n.params.rayleigh_stiffness);
  if (o.params.integrator != n.params.integrator)
    d.parameters.push_back(std::string("integrator ") + to_string(o.params.integrator) + " -> " +
                           to_string(n.params.integrator));
  const std::vector<int> match = match_nodes(o.rest, n.rest);
  std::vector<int> old_to_new(o.rest.size(), -1);
  for (size_t i = 0; i < match.size(); ++i) {
    if (match[i] < 0) continue;
    ++d.matched_nodes;
    old_to_new[size_t(match[i])] = int(i);
    d.renumbered = d.renumbered || match[i] != int(i);
  }
  d.new_nodes = int(n.rest.size()) - d.matched_nodes;
  d.removed_nodes = int(o.rest.size()) - d.matched_nodes;
  // The nodes that limit the new scene, with the limiting mode's share as weight.
  std::map<int, double> limiting;
  for (size_t k = 0; k < n.mode_nodes.size(); ++k) limiting[n.mode_nodes[k]] = n.mode_share[k];
  for (const LimitsSnapshot::Node& w : n.worst) limiting.emplace(w.node, 0.0);
  for (size_t i = 0; i < match.size(); ++i) {
    if (match[i] < 0 || n.fixed[i]) continue;
    const double a = o.node_dt_safe[size_t(match[i])], b = n.node_dt_safe[i];
    if (b < 0.99 * a) d.falls.push_back({int(i), a, b});
  }
  std::sort(d.falls.begin(), d.falls.end(), [](const LimitsDiff::Fall& a, const LimitsDiff::Fall& b) {
    return a.new_dt / a.old_dt < b.new_dt / b.old_dt || (a.new_dt / a.old_dt == b.new_dt / b.old_dt && a.node < b.node);
  });
  if (d.falls.size() > 5) d.falls.resize(5);
  for (const LimitsDiff::Fall& f : d.falls) limiting.emplace(f.node, 0.0);
  const auto weight = [&](int i) {
    const auto it = limiting.find(i);
    return it == limiting.end() ? -1.0 : it->second;
  };
  std::vector<LimitChange> all;
  const auto add = [&](double w, std::string what) {
    if (w >= 0) all.push_back({std::move(what), w});
  };
  for (size_t i = 0; i < n.rest.size(); ++i) {
    const int m = match[i];
    const std::string name = "node " + std::to_string(i) + " at " + point(n.rest[i]);
    if (m < 0) {
      add(weight(int(i)), name + ": new (mass " + format_digits(n.mass[i], 4) + ")");
      continue;
    }
    d.changed_nodes += o.mass[size_t(m)] != n.mass[i] || o.anchor[size_t(m)] != n.anchor[i] ||
                       o.fixed[size_t(m)] != n.fixed[i];
    if (o.mass[size_t(m)] != n.mass[i])
      add(weight(int(i)), name + ": mass " + ratio_text(o.mass[size_t(m)], n.mass[i]));
    if (o.anchor[size_t(m)] != n.anchor[i])
      add(weight(int(i)), name + ": anchor " + ratio_text(o.anchor[size_t(m)], n.anchor[i]));
    if (o.fixed[size_t(m)] != n.fixed[i])
      add(weight(int(i)), name + (n.fixed[i] ? ": now fixed" : ": now free"));
  }
  // Springs keyed by their old end nodes.
  std::map<std::pair<int, int>, size_t> old_springs;
  for (size_t k = 0; k < o.spring_i.size(); ++k)
    old_springs[{std::min(o.spring_i[k], o.spring_j[k]), std::max(o.spring_i[k], o.spring_j[k])}] = k;
  std::set<size_t> seen;
  for (size_t k = 0; k < n.spring_i.size(); ++k) {
    const int i = n.spring_i[k], j = n.spring_j[k];
    const int a = match[size_t(i)], b = match[size_t(j)];
    const auto it = a < 0 || b < 0 ? old_springs.end()
                                   : old_springs.find({std::min(a, b), std::max(a, b)});
    if (it != old_springs.end()) seen.insert(it->second);
    d.changed_springs += it == old_springs.end() ||
                         o.spring_kappa[it->second] != n.spring_kappa[k] ||
                         o.spring_rest_length[it->second] != n.spring_rest_length[k];
    const double w = std::max(weight(i), weight(j));
    if (w < 0) continue;
    const double length = (n.rest[size_t(j)] - n.rest[size_t(i)]).norm();
    const std::string name = "spring " + std::to_string(i) + "-" + std::to_string(j) + " " +
                             point(n.rest[size_t(i)]) + "-" + point(n.rest[size_t(j)]);
    if (it == old_springs.end()) {
      add(w, name + ": new, kappa " + format_digits(n.spring_kappa[k], 4) + ", length " +
                 format_digits(length, 4) + " cm");
      continue;
    }
    if (o.spring_kappa[it->second] != n.spring_kappa[k])
      add(w, name + ": kappa " + ratio_text(o.spring_kappa[it->second], n.spring_kappa[k]));
    if (o.spring_rest_length[it->second] != n.spring_rest_length[k])
      add(w, name + ": rest length " +
                 ratio_text(o.spring_rest_length[it->second], n.spring_rest_length[k]));
  }
  for (const auto& [ends, k] : old_springs) {
    if (seen.count(k)) continue;
    ++d.changed_springs;
    const int a = old_to_new[size_t(ends.first)], b = old_to_new[size_t(ends.second)];
    const double w = std::max(a < 0 ? -1.0 : weight(a), b < 0 ? -1.0 : weight(b));
    add(w, "spring between old nodes " + std::to_string(ends.first) + "-" +
               std::to_string(ends.second) + " " + point(o.rest[size_t(ends.first)]) + "-" +
               point(o.rest[size_t(ends.second)]) + ": removed");
  }
  std::stable_sort(all.begin(), all.end(),
                   [](const LimitChange& a, const LimitChange& b) { return a.weight > b.weight; });
  if (all.size() > 10) all.resize(10);
  d.changes = std::move(all);
  return d;
}

namespace {

template <class T>
void json_array(std::ostream& out, const char* key, const std::vector<T>& v, bool last = false) {
  out << '"' << key << "\":[";
  for (size_t k = 0; k < v.size(); ++k) {
    if (k) out << ',';
    if constexpr (std::is_floating_point_v<T>) out << json_limit_text(v[k]);
    else out << static_cast<long long>(v[k]);
  }
  out << (last ? "]" : "],");
}

}  // namespace

void write_limits_json(std::ostream& out, const LimitsSnapshot& s) {
  const Params& p = s.params;
  out << "{\"format\":\"dampbound-limits\",\"version\":1,\"scene\":" << json_string(s.scene)
      << ",\"integrator\":" << json_string(to_string(p.integrator)) << ",\"params\":{";
  const std::pair<const char*, double> params[] = {
      {"m", p.m}, {"kappa", p.kappa}, {"gamma", p.gamma}, {"dt", p.dt}, {"kd", p.kd},
      {"rayleigh_mass", p.rayleigh_mass}, {"rayleigh_stiffness", p.rayleigh_stiffness}};
  for (size_t k = 0; k < std::size(params); ++k)
    out << (k ? "," : "") << '"' << params[k].first << "\":" << json_limit_text(params[k].second);
  out << "},\"method\":" << json_string(s.method) << ",\"dt_limit\":" << json_limit_text(s.dt_limit)
      << ",\"gamma_lo\":" << json_limit_text(s.gamma_lo)
      << ",\"gamma_hi\":" << json_limit_text(s.gamma_hi)
      << ",\"dt_safe\":" << json_limit_text(s.dt_safe) << ",\"dt_safe_node\":" << s.dt_safe_node
      << ",\"worst\":[";
  for (size_t k = 0; k < s.worst.size(); ++k)
    out << (k ? "," : "") << "{\"node\":" << s.worst[k].node
        << ",\"dt_safe\":" << json_limit_text(s.worst[k].dt_safe)
        << ",\"cause\":" << json_string(s.worst[k].cause) << "}";
  out << "],\"mode\":{";
  json_array(out, "nodes", s.mode_nodes);
  json_array(out, "share", s.mode_share, true);
  out << "},\"nodes\":{";
  std::vector<double> xyz;
  for (const Vec3& r : s.rest) xyz.insert(xyz.end(), {r.x(), r.y(), r.z()});
  json_array(out, "rest", xyz);
  json_array(out, "mass", s.mass);
  json_array(out, "anchor", s.anchor);
  json_array(out, "dt_safe", s.node_dt_safe);
  json_array(out, "fixed", s.fixed, true);
  out << "},\"springs\":{";
  json_array(out, "i", s.spring_i);
  json_array(out, "j", s.spring_j);
  json_array(out, "kappa", s.spring_kappa);
  json_array(out, "rest_length", s.spring_rest_length, true);
  out << "}}\n";
}

LimitsSnapshot read_limits_json(const std::string& text, const std::string& path) {
  const JsonValue root = parse_json(text, path);
  const auto member = [&](const JsonValue& v, const std::string& key) -> const JsonValue& {
    const JsonValue* m = v.find(key);
    if (!m) throw InputError(path + ": not a dampbound limits baseline (no \"" + key + "\"; "
                             "write one with dampbound diff SCENE --save FILE)");
    return *m;
  };
  const JsonValue* format = root.find("format");
  if (!format || format->string != "dampbound-limits")
    throw InputError(path + ": not a dampbound limits baseline (write one with dampbound diff "
                            "SCENE --save FILE)");
  if (json_limit(member(root, "version"), path, "version") != 1)
    throw InputError(path + ": baseline version must be 1");
  const auto number = [&](const JsonValue& v, const std::string& key) {
    return json_limit(member(v, key), path, key);
  };
  const auto numbers = [&](const JsonValue& v, const std::string& key) {
    const JsonValue& a = member(v, key);
    if (a.kind != JsonValue::Kind::array) throw InputError(path + ": " + key + " must be an array");
    std::vector<double> out;
    for (const JsonValue& e : a.array) out.push_back(json_limit(e, path, key));
    return out;
  };
  const auto integers = [&](const JsonValue& v, const std::string& key, long long lo, long long hi) {
    std::vector<int> out;
    for (double x : numbers(v, key)) {
      if (!(x >= double(lo) && x <= double(hi)) || x != std::floor(x))
        throw InputError(path + ": " + key + " holds " + format_number(x) + ", not an index");
      out.push_back(int(x));
    }
    return out;
  };
  LimitsSnapshot s;
  s.scene = member(root, "scene").string;
  const auto integrator = parse_integrator(member(root, "integrator").string);
  if (!integrator) throw InputError(path + ": unknown integrator");
  const JsonValue& p = member(root, "params");
  s.params.integrator = *integrator;
  s.params.m = number(p, "m");
  s.params.kappa = number(p, "kappa");
  s.params.gamma = number(p, "gamma");
  s.params.dt = number(p, "dt");
  s.params.kd = number(p, "kd");
  s.params.rayleigh_mass = number(p, "rayleigh_mass");
  s.params.rayleigh_stiffness = number(p, "rayleigh_stiffness");
  s.method = member(root, "method").string;
  s.dt_limit = number(root, "dt_limit");
  s.gamma_lo = number(root, "gamma_lo");
  s.gamma_hi = number(root, "gamma_hi");
  s.dt_safe = number(root, "dt_safe");
  const JsonValue& nodes = member(root, "nodes");
  const std::vector<double> xyz = numbers(nodes, "rest");
  const size_t n = xyz.size() / 3;
  s.mass = numbers(nodes, "mass");
  s.anchor = numbers(nodes, "anchor");
  s.node_dt_safe = numbers(nodes, "dt_safe");
  const std::vector<int> fixed = integers(nodes, "fixed", 0, 1);
  if (xyz.size() != 3 * n || s.mass.size() != n || s.anchor.size() != n ||
      s.node_dt_safe.size() != n || fixed.size() != n)
    throw InputError(path + ": nodes' arrays differ in length");
  for (size_t i = 0; i < n; ++i) s.rest.emplace_back(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  s.fixed.assign(fixed.begin(), fixed.end());
  const long long last = static_cast<long long>(n) - 1;
  s.dt_safe_node = int(json_limit(member(root, "dt_safe_node"), path, "dt_safe_node"));
  for (const JsonValue& w : member(root, "worst").array) {
    const double node = json_limit(member(w, "node"), path, "worst node");
    if (!(node >= 0 && node <= double(last))) throw InputError(path + ": worst node out of range");
    s.worst.push_back({int(node), number(w, "dt_safe"), member(w, "cause").string});
  }
  const JsonValue& mode = member(root, "mode");
  s.mode_nodes = integers(mode, "nodes", 0, last);
  s.mode_share = numbers(mode, "share");
  if (s.mode_share.size() != s.mode_nodes.size()) throw InputError(path + ": mode's arrays differ in length");
  const JsonValue& springs = member(root, "springs");
  s.spring_i = integers(springs, "i", 0, last);
  s.spring_j = integers(springs, "j", 0, last);
  s.spring_kappa = numbers(springs, "kappa");
  s.spring_rest_length = numbers(springs, "rest_length");
  if (s.spring_j.size() != s.spring_i.size() || s.spring_kappa.size() != s.spring_i.size() ||
      s.spring_rest_length.size() != s.spring_i.size())
    throw InputError(path + ": springs' arrays differ in length");
  return s;
}

}  // namespace dampbound
