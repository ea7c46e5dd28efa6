#pragma once
// Sweep grids: axes of exact decimal values (m, kappa, gamma or zeta, dt, factor, and SPEC 10's
// kd, rayleigh_mass, rayleigh_stiffness), the trials they span, and the similarity classes of
// SPEC 6 and 10 (trials sharing kappa/m, gamma/m, kd/m, alpha, beta and dt are one trial),
// found exactly with integers and gcds, never by comparing doubles.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/sweep/kernel.hpp"
#include "dampbound/run/protocol.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound {

/// A decimal number held exactly: value = digits * 10^-scale, scale >= 0, normalised (no
/// trailing zero digit while scale > 0), so equal values have equal fields.
struct Decimal {
  std::int64_t digits = 0;
  int scale = 0;
  std::string text() const;  ///< plain decimal notation, e.g. "0.0003"
  double value() const;      ///< the double nearest to the decimal (correctly rounded)
  bool operator==(const Decimal& o) const { return digits == o.digits && scale == o.scale; }
};

/// Parses "0.0003", "3e-4", "12". Throws InputError naming `flag` when it is not a finite
/// decimal number, or has more than 17 significant digits or 18 decimal places.
Decimal parse_decimal(const std::string& text, const std::string& flag);

/// One sweep axis: a comma-separated list whose items are numbers or inclusive ranges
/// A:B:STEP (A, A+STEP, ... up to B). Duplicates are kept (they become equivalent trials).
struct Axis {
  std::string flag;  ///< "--m", "--kappa", ... for messages
  std::string spec;  ///< as given
  std::vector<Decimal> values;
};

/// What an axis admits.
enum class AxisDomain { positive, non_negative };

/// Parses an axis; throws InputError naming `flag` for an empty or inverted range, a step of
/// zero or below, a value outside the domain, or more than `max_values` values.
Axis parse_axis(const std::string& flag, const std::string& spec, AxisDomain domain,
                std::uint64_t max_values = 100000000);

/// How gamma is given: as fractions zeta of the lower bound 2 sqrt(m kappa) (paper eq. 5), or
/// as absolute values.
enum class GammaMode { zeta, absolute };

/// Everything that defines a sweep except the scene.
struct SweepSpec {
  Axis m, kappa;
  GammaMode gamma_mode = GammaMode::absolute;
  Axis gamma;  ///< zeta values or absolute gamma values
  Axis dt, factor;
  /// SPEC 10's damping axes; an empty axis is not swept (the scene's value holds in every
  /// trial). A sweep with none of them writes exactly the CSV it wrote before they existed.
  Axis kd, rayleigh_mass, rayleigh_stiffness;
  bool has_damping_axes() const {
    return !kd.values.empty() || !rayleigh_mass.values.empty() ||
           !rayleigh_stiffness.values.empty();
  }
  DampingPolicy policy = DampingPolicy::fixed;
  StopRules rules;
  bool allow_similarity = true;
};

/// The trials of a sweep: index t -> (rayleigh_stiffness, rayleigh_mass, kd, dt, factor, gamma,
/// m, kappa) with kappa varying fastest (an axis that is not swept counts as one value).
class SweepGrid {
 public:
  explicit SweepGrid(SweepSpec spec);

  const SweepSpec& spec() const { return spec_; }
  std::uint64_t trials() const { return trials_; }

  struct Index {
    size_t dt, factor, gamma, m, kappa;
    size_t kd = 0, rayleigh_mass = 0, rayleigh_stiffness = 0;  ///< 0 where not swept
  };
  Index index(std::uint64_t trial) const;
  /// m, kappa and dt as their decimals; gamma = zeta * 2 sqrt(m kappa) (lower_bound()) in
  /// zeta mode, else the decimal; the swept SPEC 10 damping (unswept ones stay unset).
  TrialParams params(std::uint64_t trial) const;
  /// gamma / (2 sqrt(m kappa)): the axis value in zeta mode, computed otherwise.
  double zeta(std::uint64_t trial) const;

 private:
  SweepSpec spec_;
  std::uint64_t trials_ = 0;
};

/// Why trials with equal kappa/m, gamma/m and dt may not be merged on this scene (nullopt
/// when they may): SPEC 6 needs uniform m, kappa, gamma (every mass, gamma and stiffness scale
/// equal) and no external force. Dividing eq. 1 by m then leaves only kappa/m and gamma/m.
/// SPEC 10: a scene's kd held across trials of different m is not similar (kd/m differs)
/// unless `kd_swept` (the kd axis then enters the class key); swept dashpots need uniform
/// dashpot scales.
std::optional<std::string> similarity_unavailable(const SceneSpec& scene, bool kd_swept = false);

/// Similarity classes of a grid.
struct TrialClasses {
  bool similarity = false;                    ///< false: every trial is its own class
  std::string reason;                         ///< why similarity is off, when it is
  std::vector<std::uint32_t> class_of;        ///< per trial
  std::vector<std::uint64_t> representative;  ///< per class: its first trial (the one run)
  std::size_t count() const { return representative.size(); }
};

/// Finds the classes: with m = a q, kappa = b q (and gamma = c q) on one decimal quantum q,
/// the class key is the reduced fraction b/a with the zeta value (gamma/m = 2 zeta sqrt(b/a)),
/// or the reduced triple (a, b, c) for absolute gamma, with kd = d q in the same reduction
/// (kd/m = d/a) when kd is swept; plus dt, alpha and beta (SPEC 10), and factor under policy
/// upper. Policies upper and lower ignore the user's gamma, so it is left out of their key.
/// `scene_reason` (from similarity_unavailable) turns similarity off.
TrialClasses find_classes(const SweepGrid& grid, const std::optional<std::string>& scene_reason);

/// Bytes of memory the classes of a grid with `trials` trials need at most.
std::uint64_t class_memory_bound(std::uint64_t trials);

}  // namespace dampbound
