#pragma once
// The user's parameters (paper eq. 1): mass m, stiffness kappa, damping gamma, time step dt,
// and how the effective damping is chosen from gamma each step (SPEC 4).
#include "dampbound/physics/export.hpp"
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace dampbound DAMPBOUND_API {

/// How the effective damping of node i at step t is chosen from the user's gamma (SPEC 4).
enum class DampingPolicy {
  fixed,  ///< gamma as given
  clamp,  ///< gamma clamped into [gamma_lo_i, gamma_hi_i]; gamma_hi_i when the interval is empty
  upper,  ///< factor * gamma_hi_i (0 when gamma_hi_i is infinite)
  lower,  ///< gamma_lo_i
  safe,   ///< gamma clamped into [gamma_lo_i, gamma_safe_i] (SPEC 9); gamma_safe_i when empty
};

/// The time integrator. The paper's semi-implicit Euler (SPEC 2) is the default and the
/// reference; the others are options for comparison (SPEC 2, "welcome as options").
enum class Integrator {
  semi_implicit_euler,  ///< paper eqs. 3-4: v += a dt; x += v_new dt
  forward_euler,        ///< x += v_old dt; v += a dt
  verlet,               ///< velocity Verlet (central differences)
  rk4,                  ///< classic 4th-order Runge-Kutta on (x, v)
  implicit_euler,       ///< backward Euler, one Newton step with CG (Baraff-Witkin)
};

/// One row per integrator: its name and what the analyses may say about it. Code asks these
/// questions instead of comparing integrators by name; the scene reader, the scene-key table,
/// the CLI's flags and Python read the names from here. A new integrator is its enum value and
/// row here, its step (core/physics/integrate.cpp, a switch the compiler checks), its
/// linearised step (core/analysis/linear_stability_modes.cpp, likewise) and its test.
struct IntegratorTraits {
  Integrator id;
  const char* name;  ///< what flags, menus and files say
  /// The paper's step: SPEC 7's predicate, the symmetric index at non-uniform damping, the
  /// safe bound (SPEC 9, 10) and the general damping matrix's limits apply.
  bool paper_step;
  /// The velocity update v' = v + a dt from the forces at t (the paper's step and forward
  /// Euler): eq. 6 is derived for it, and the radius over an interval of rates is decided at
  /// the interval's ends.
  bool euler_velocity_update;
  /// The sweep's batched kernel steps it lane by lane, bit-identical to step().
  bool batched_kernel;
  /// Backward Euler: unconditionally stable where K is positive semi-definite; it solves
  /// with K's compression clamped.
  bool implicit;
};

/// In the order menus and flags list them.     paper  Euler v  kernel implicit
inline constexpr IntegratorTraits kIntegratorTable[] = {
    {Integrator::semi_implicit_euler, "semi-implicit-euler", true, true, true, false},
    {Integrator::forward_euler, "forward-euler", false, true, true, false},
    {Integrator::verlet, "verlet", false, false, false, false},
    {Integrator::rk4, "rk4", false, false, false, false},
    {Integrator::implicit_euler, "implicit-euler", false, false, false, true},
};

namespace detail {
template <std::size_t... I>
constexpr std::array<Integrator, sizeof...(I)> integrator_ids(std::index_sequence<I...>) {
  return {kIntegratorTable[I].id...};
}
}  // namespace detail
/// Every integrator, in the table's order.
inline constexpr auto kIntegrators =
    detail::integrator_ids(std::make_index_sequence<std::size(kIntegratorTable)>{});

/// The row of integrator i (every value of Integrator has one; std::invalid_argument otherwise).
const IntegratorTraits& integrator_traits(Integrator i);

/// Uniform parameters; per-node and per-spring scales from the scene multiply them.
struct Params {
  double m = 0.001;      ///< node mass (mass unit)
  double kappa = 0.001;  ///< spring and anchor stiffness (mass unit / s^2)
  double gamma = 0.002;  ///< user's viscous damping (mass unit / s)
  /// The nodal damping ratio given in place of gamma (SPEC 10): gamma_i = zeta * 2 sqrt(m_i
  /// kappa_i). resolve_zeta() (core/physics/damping_ratio.hpp) turns it into gamma and clears it.
  std::optional<double> zeta;
  double dt = 0.05;      ///< time step (s)
  /// SPEC 10: dashpots along springs and anchors, kd_ij = kd * kd_scale (mass unit / s).
  double kd = 0;
  double rayleigh_mass = 0;       ///< SPEC 10: Rayleigh alpha (1/s): force -alpha m_i v_i
  double rayleigh_stiffness = 0;  ///< SPEC 10: Rayleigh beta (s): force -beta (K(x) v)_i
  DampingPolicy policy = DampingPolicy::fixed;
  double factor = 1.0;  ///< multiplier of gamma_hi for DampingPolicy::upper
  Integrator integrator = Integrator::semi_implicit_euler;
};

/// The defaults: the paper's Fig. 1 setting at gamma = 2*sqrt(m*kappa).
inline Params default_params() { return Params{}; }

/// Every policy and every integrator, in the order menus and flags list them.
inline constexpr DampingPolicy kPolicies[] = {DampingPolicy::fixed, DampingPolicy::clamp,
                                              DampingPolicy::upper, DampingPolicy::lower,
                                              DampingPolicy::safe};

const char* to_string(DampingPolicy p);
const char* to_string(Integrator i);
/// Whether the policy's effective gamma_i depends on the user's gamma (SPEC 4, 9): fixed,
/// clamp and safe start from it; upper and lower ignore it. Sweeps key their similarity
/// classes on it (SPEC 6): two trials that differ only in gamma are one trial only where
/// the policy ignores gamma.
bool uses_user_gamma(DampingPolicy p);
/// The names of kPolicies and kIntegrators (what flags and menus accept).
std::vector<std::string> policy_names();
std::vector<std::string> integrator_names();
/// The names joined for a message: "a, b, c or d".
std::string one_of(const std::vector<std::string>& names);
/// Parses "fixed" | "clamp" | "upper" | "lower" | "safe"; nullopt when unknown.
std::optional<DampingPolicy> parse_policy(const std::string& s);
/// Parses a name of kIntegratorTable; nullopt when unknown.
std::optional<Integrator> parse_integrator(const std::string& s);

/// The one rule for a number the CLI's flags, the scene files and the API take: nullopt when
/// x is finite and > 0 (>= 0 with allow_zero), else what is wrong: "must be finite",
/// "must be > 0" or "must be >= 0" (callers put the name of the flag or parameter first).
std::optional<std::string> number_problem(double x, bool allow_zero);

/// What makes the parameters unusable, naming the parameter ("dt must be > 0"); nullopt when
/// they are usable. m, kappa, dt: finite and > 0; gamma, factor: finite and >= 0.
std::optional<std::string> validate(const Params& p);

}  // namespace dampbound
