// dampbound bounds: the paper's bounds (eqs. 5, 6) and the runtime check (sec. 5) for given
// parameters.
#include <cstdio>
#include <memory>
#include <sstream>

#include "app/commands.hpp"
#include "app/options.hpp"
#include "core/bounds.hpp"
#include "core/error.hpp"
#include "core/io.hpp"

namespace dampbound::app {
namespace {

struct BoundsArgs {
  double m = 0, kappa = 0, dt = 0, gamma = 0;
  std::string v, force;
  CLI::Option* gamma_opt = nullptr;
};

Vec3 parse_vec3(const std::string& text, const char* flag) {
  std::istringstream in(text);
  Vec3 out;
  std::string part;
  for (int k = 0; k < 3; ++k) {
    if (!std::getline(in, part, ',')) break;
    try {
      size_t used = 0;
      out[k] = std::stod(part, &used);
      if (used != part.size() || !std::isfinite(out[k])) throw 0;
    } catch (...) {
      throw InputError(std::string(flag) + ": '" + text + "' is not three finite numbers x,y,z");
    }
    if (k == 2 && !in.eof()) break;
    if (k == 2) return out;
  }
  throw InputError(std::string(flag) + ": '" + text + "' is not three numbers x,y,z");
}

int run(const BoundsArgs& a) {
  const double lo = lower_bound(a.m, a.kappa);
  std::printf("lower bound (eq. 5)   gamma_lo = 2*sqrt(m*kappa) = %s\n", format_number(lo).c_str());
  if (a.v.empty() != a.force.empty()) throw InputError("--v and --force go together");
  if (a.v.empty()) return 0;
  const Vec3 v = parse_vec3(a.v, "--v"), f = parse_vec3(a.force, "--force");
  const double hi = upper_bound(v, f, a.m, a.dt);
  std::printf("upper bound (eq. 6)   gamma_hi = |v*m/dt + F|/|v| = %s%s\n",
              format_number(hi).c_str(), v.norm() == 0 ? " (v = 0: damping has no effect)" : "");
  const bool stabilisable = !(lo > hi);
  std::printf("check (sec. 5)        %s\n",
              stabilisable ? "stabilisable: gamma_lo <= gamma_hi"
                           : "UNSTABILISABLE: gamma_lo > gamma_hi, no damping satisfies both");
  if (a.gamma_opt->count()) {
    const bool inside = a.gamma >= lo && a.gamma <= hi;
    std::printf("gamma = %s          %s\n", format_number(a.gamma).c_str(),
                inside ? "within the bounds" : "outside the bounds");
  }
  return 0;
}

std::function<int()> setup(CLI::App& root) {
  auto a = std::make_shared<BoundsArgs>();
  CLI::App* cmd = root.add_subcommand(
      "bounds", "Print the paper's damping bounds: the lower bound 2*sqrt(m*kappa) (eq. 5) and, "
                "given a velocity and force, the upper bound |v*m/dt+F|/|v| (eq. 6) and the "
                "runtime check (sec. 5).");
  cmd->add_option("--m", a->m, "node mass (mass unit)")->required()->check(finite_positive());
  cmd->add_option("--kappa", a->kappa, "stiffness (mass unit/s^2)")
      ->required()
      ->check(finite_positive());
  cmd->add_option("--dt", a->dt, "time step (s)")->required()->check(finite_positive());
  cmd->add_option("--v", a->v, "node velocity x,y,z (cm/s)");
  cmd->add_option("--force", a->force, "internal (spring) force on the node x,y,z (mass unit cm/s^2)");
  a->gamma_opt = cmd->add_option("--gamma", a->gamma, "a damping to test against the bounds")
                     ->check(finite_non_negative());
  return [a] { return run(*a); };
}

const bool registered = register_command("bounds", setup);

}  // namespace
}  // namespace dampbound::app
