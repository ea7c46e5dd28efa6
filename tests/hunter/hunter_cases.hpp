#pragma once
// The hunter's scenes: small random mass-spring models from one 64-bit seed, the same on every
// machine (a splitmix64 stream and our own uniform draws; no <random> distribution, whose
// output the standard leaves to the library).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>

#include "dampbound/physics/model.hpp"
#include "dampbound/physics/params.hpp"

namespace dampbound::hunt {

class Draw {
 public:
  explicit Draw(std::uint64_t seed) : s_(seed) {}
  std::uint64_t bits() {  // splitmix64
    std::uint64_t z = (s_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  double unit() { return static_cast<double>(bits() >> 11) * 0x1.0p-53; }  ///< [0, 1)
  double uniform(double a, double b) { return a + (b - a) * unit(); }
  double log_uniform(double a, double b) { return std::exp(uniform(std::log(a), std::log(b))); }
  bool chance(double p) { return unit() < p; }
  int below(int n) { return static_cast<int>(bits() % static_cast<std::uint64_t>(n)); }

 private:
  std::uint64_t s_;
};

/// One random case: a model, its parameters at rest, and a line that says what it is.
struct Case {
  std::uint64_t seed = 0;
  ModelSpec spec;
  Params params;
  std::string what;
};

inline Case make_case(std::uint64_t seed) {
  Draw d(seed);
  Case c;
  c.seed = seed;
  ModelSpec& s = c.spec;
  const int n = 2 + d.below(9);
  const bool flat = d.chance(0.3);
  const double len = d.chance(0.1) ? d.log_uniform(1e-3, 1e3) : d.log_uniform(0.1, 10);
  for (int i = 0; i < n; ++i)
    add_node(s, len * Vec3(d.unit(), flat ? 0.0 : d.unit(), d.unit()));
  for (int i = 1; i < n; ++i) add_spring(s, d.below(i), i);  // a random tree
  for (int e = d.below(n + 1); e > 0; --e) {  // extra springs, no pair twice (as scene files)
    const int a = d.below(n), b = d.below(n);
    bool twice = a == b;
    for (const Spring& sp : s.springs)
      twice = twice || (sp.i == a && sp.j == b) || (sp.i == b && sp.j == a);
    if (!twice) add_spring(s, a, b);
  }
  const bool varied = d.chance(0.5);
  for (Spring& sp : s.springs) {
    if (varied) sp.kappa_scale = d.log_uniform(0.1, 10);
    if (d.chance(0.3)) sp.kd_scale = d.chance(0.2) ? 0.0 : d.log_uniform(0.1, 10);
  }
  int fixed = 0;
  for (int i = 0; i < n; ++i) {
    const size_t k = static_cast<size_t>(i);
    if (d.chance(0.5)) s.anchor_scale[k] = d.log_uniform(0.05, 5);
    if (varied) s.mass_scale[k] = d.log_uniform(0.1, 10);
    if (d.chance(0.15)) s.gamma_scale[k] = d.chance(0.3) ? 0.0 : d.log_uniform(0.2, 5);
    if (i > 0 && d.chance(0.2)) s.fixed[k] = 1, ++fixed;
  }
  // Half the cases hold every free node by an anchor (K positive definite); the others keep
  // zero modes (motions across a spring at rest), whose z = 1 the checks treat as marginal.
  if (fixed == 0) s.fixed[0] = 1;
  if (d.chance(0.5))
    for (size_t k = 0; k < s.anchor_scale.size(); ++k)
      if (!s.fixed[k] && s.anchor_scale[k] == 0) s.anchor_scale[k] = d.log_uniform(0.01, 1);
  Params& p = c.params;
  const bool extreme = d.chance(0.12);
  p.m = extreme ? std::pow(10.0, d.uniform(-60, 60)) : d.log_uniform(1e-4, 1e2);
  p.kappa = extreme ? std::pow(10.0, d.uniform(-60, 60)) : d.log_uniform(1e-4, 1e2);
  const double omega = std::sqrt(p.kappa / p.m), crit = 2 * std::sqrt(p.m * p.kappa);
  const int kinds = d.below(8);  // bits: nodal, dashpot, Rayleigh
  p.gamma = (kinds & 1) ? d.uniform(0, 2.5) * crit : 0.0;
  p.kd = (kinds & 2) ? d.uniform(0, 1.5) * crit : 0.0;
  if (kinds & 4) {
    if (d.chance(0.7)) p.rayleigh_mass = d.uniform(0, 2) * omega;
    if (d.chance(0.7)) p.rayleigh_stiffness = d.uniform(0, 0.6) / omega;
  }
  p.dt = d.log_uniform(0.02, 3) / omega;
  p.integrator = kIntegrators[d.below(5)];
  std::ostringstream w;
  w.precision(17);
  w << "seed " << seed << ": " << n << " nodes, " << s.springs.size() << " springs, "
    << to_string(p.integrator) << ", m " << p.m << " kappa " << p.kappa << " gamma " << p.gamma
    << " kd " << p.kd << " alpha " << p.rayleigh_mass << " beta " << p.rayleigh_stiffness
    << " dt " << p.dt;
  c.what = w.str();
  return c;
}

/// The case as a scene file (docs/scene-format.md) that `dampbound bounds`, `run` and `suggest`
/// read: what to reproduce a contradiction with.
inline std::string scene_toml(const Case& c) {
  std::ostringstream o;
  o.precision(17);
  o << std::scientific;  // a TOML float even where the value is whole
  o << "# guarantee hunter, " << c.what << "\nname = \"hunted-" << c.seed << "\"\n";
  const ModelSpec& s = c.spec;
  int watch = -1;
  for (size_t i = 0; i < s.rest.size(); ++i) {
    o << "\n[[node]]\nx = [" << s.rest[i].x() << ", " << s.rest[i].y() << ", " << s.rest[i].z()
      << "]\n";
    if (s.fixed[i]) o << "fixed = true\n";
    else if (watch < 0) watch = static_cast<int>(i);
    o << "mass_scale = " << s.mass_scale[i] << "\ngamma_scale = " << s.gamma_scale[i]
      << "\nanchor_scale = " << s.anchor_scale[i] << "\n";
  }
  for (const Spring& sp : s.springs)
    o << "\n[[spring]]\nnodes = [" << sp.i << ", " << sp.j << "]\nrest_length = " << sp.rest_length
      << "\nkappa_scale = " << sp.kappa_scale << "\nkd_scale = " << sp.kd_scale << "\n";
  const Params& p = c.params;
  o << "\n[params]\nm = " << p.m << "\nkappa = " << p.kappa << "\ngamma = " << p.gamma
    << "\nkd = " << p.kd << "\nrayleigh_mass = " << p.rayleigh_mass
    << "\nrayleigh_stiffness = " << p.rayleigh_stiffness << "\ndt = " << p.dt
    << "\nintegrator = \"" << to_string(p.integrator) << "\"\n";
  double scale = 0;
  for (const Vec3& x : s.rest) scale = std::max(scale, x.norm());
  o << "\n[[perturb]]\nnode = " << watch << "\ndisplacement = [0.0, " << 1e-3 * scale
    << ", 0.0]\n";
  return o.str();
}

}  // namespace dampbound::hunt
