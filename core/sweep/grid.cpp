#include "core/sweep/grid.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <numeric>
#include <unordered_map>

#include "core/io/format.hpp"
#include "dampbound/physics/bounds.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound {

namespace {

constexpr std::int64_t kMaxDigits = 999999999999999999;  // 18 nines: products stay in int64
constexpr int kMaxScale = 18;

bool times_ten_pow(std::int64_t& x, int p) {
  for (int k = 0; k < p; ++k) {
    if (x > kMaxDigits / 10 || x < -kMaxDigits / 10) return false;
    x *= 10;
  }
  return true;
}

Decimal normalised(std::int64_t digits, int scale) {
  while (scale > 0 && digits % 10 == 0) {
    digits /= 10;
    --scale;
  }
  if (digits == 0) scale = 0;
  return {digits, scale};
}

/// a and b as integers on their common (finer) quantum.
bool common(const Decimal& a, const Decimal& b, std::int64_t& ia, std::int64_t& ib, int& scale) {
  scale = std::max(a.scale, b.scale);
  ia = a.digits;
  ib = b.digits;
  return times_ten_pow(ia, scale - a.scale) && times_ten_pow(ib, scale - b.scale);
}

[[noreturn]] void bad(const std::string& flag, const std::string& msg) {
  throw InputError(flag + ": " + msg);
}

}  // namespace

std::string Decimal::text() const {
  std::string s = std::to_string(digits < 0 ? -digits : digits);
  if (scale > 0) {
    if (static_cast<int>(s.size()) <= scale)
      s.insert(0, static_cast<size_t>(scale + 1) - s.size(), '0');
    s.insert(s.size() - static_cast<size_t>(scale), ".");
  }
  return digits < 0 ? "-" + s : s;
}

double Decimal::value() const {
  return c_strtod(text().c_str(), nullptr);
}

Decimal parse_decimal(const std::string& text, const std::string& flag) {
  const std::string what = "'" + text + "' is not a decimal number";
  size_t p = 0;
  bool negative = false;
  if (p < text.size() && (text[p] == '+' || text[p] == '-')) negative = text[p++] == '-';
  std::string mantissa;
  int fraction = 0;
  bool point = false, any = false;
  for (; p < text.size(); ++p) {
    const char c = text[p];
    if (std::isdigit(static_cast<unsigned char>(c))) {
      any = true;
      if (point) ++fraction;
      if (!(mantissa.empty() && c == '0')) mantissa += c;  // drop leading zeros
    } else if (c == '.' && !point) {
      point = true;
    } else {
      break;
    }
  }
  if (!any) bad(flag, what);
  long exponent = 0;
  if (p < text.size() && (text[p] == 'e' || text[p] == 'E')) {
    ++p;
    const size_t start = p;
    if (p < text.size() && (text[p] == '+' || text[p] == '-')) ++p;
    if (p == text.size() || !std::isdigit(static_cast<unsigned char>(text[p]))) bad(flag, what);
    while (p < text.size() && std::isdigit(static_cast<unsigned char>(text[p]))) ++p;
    exponent = std::strtol(text.substr(start, p - start).c_str(), nullptr, 10);
    if (exponent > 40 || exponent < -40) bad(flag, "'" + text + "': exponent out of range");
  }
  if (p != text.size()) bad(flag, what);
  // Leading zeros were dropped; trailing zeros of the fraction are dropped by normalising.
  while (!mantissa.empty() && mantissa.back() == '0' && fraction > 0) {
    mantissa.pop_back();
    --fraction;
  }
  if (mantissa.size() > 17) bad(flag, "'" + text + "' has more than 17 significant digits");
  std::int64_t digits = mantissa.empty() ? 0 : std::stoll(mantissa);
  long scale = fraction - exponent;
  if (scale < 0) {
    if (!times_ten_pow(digits, static_cast<int>(-scale))) bad(flag, "'" + text + "' is too large");
    scale = 0;
  }
  if (scale > kMaxScale) bad(flag, "'" + text + "' has more than 18 decimal places");
  Decimal d = normalised(negative ? -digits : digits, static_cast<int>(scale));
  if (!std::isfinite(d.value())) bad(flag, "'" + text + "' is not finite");
  return d;
}

Axis parse_axis(const std::string& flag, const std::string& spec, AxisDomain domain,
                std::uint64_t max_values) {
  Axis axis{flag, spec, {}};
  if (spec.empty()) bad(flag, "no values given");
  auto check_domain = [&](const Decimal& d, const std::string& item) {
    if (domain == AxisDomain::positive && d.digits <= 0)
      bad(flag, "'" + item + "': values must be > 0");
    if (domain == AxisDomain::non_negative && d.digits < 0)
      bad(flag, "'" + item + "': values must be >= 0");
  };
  size_t start = 0;
  while (start <= spec.size()) {
    size_t comma = spec.find(',', start);
    if (comma == std::string::npos) comma = spec.size();
    const std::string item = spec.substr(start, comma - start);
    start = comma + 1;
    if (item.empty()) bad(flag, "empty item in '" + spec + "'");
    const size_t c1 = item.find(':');
    if (c1 == std::string::npos) {
      const Decimal d = parse_decimal(item, flag);
      check_domain(d, item);
      axis.values.push_back(d);
    } else {
      const size_t c2 = item.find(':', c1 + 1);
      if (c2 == std::string::npos || item.find(':', c2 + 1) != std::string::npos)
        bad(flag, "'" + item + "': a range is A:B:STEP");
      const Decimal a = parse_decimal(item.substr(0, c1), flag);
      const Decimal b = parse_decimal(item.substr(c1 + 1, c2 - c1 - 1), flag);
      const Decimal st = parse_decimal(item.substr(c2 + 1), flag);
      if (st.digits <= 0) bad(flag, "'" + item + "': the step must be > 0");
      check_domain(a, item);
      std::int64_t ia = 0, ib = 0, is = 0, ia2 = 0;
      int scale = 0, scale2 = 0;
      if (!common(a, b, ia, ib, scale) || !common(Decimal{ia, scale}, st, ia2, is, scale2) ||
          !times_ten_pow(ib, scale2 - scale))
        bad(flag, "'" + item + "': too many decimal places");
      if (ib < ia2) bad(flag, "'" + item + "': empty range (B < A)");
      const std::uint64_t count = static_cast<std::uint64_t>((ib - ia2) / is) + 1;
      if (count > max_values || axis.values.size() + count > max_values)
        bad(flag, "'" + item + "' has " + std::to_string(count) + " values, more than " +
                      std::to_string(max_values));
      for (std::uint64_t k = 0; k < count; ++k)
        axis.values.push_back(normalised(ia2 + static_cast<std::int64_t>(k) * is, scale2));
    }
    if (comma == spec.size()) break;
  }
  return axis;
}

SweepGrid::SweepGrid(SweepSpec spec) : spec_(std::move(spec)) {
  constexpr std::uint64_t kMaxTrials = 0xFFFFFFFFull;  // class ids are 32-bit
  std::uint64_t n = 1;
  for (const Axis* a : {&spec_.dt, &spec_.factor, &spec_.gamma, &spec_.m, &spec_.kappa, &spec_.kd,
                        &spec_.rayleigh_mass, &spec_.rayleigh_stiffness}) {
    const bool optional = a == &spec_.kd || a == &spec_.rayleigh_mass || a == &spec_.rayleigh_stiffness;
    if (a->values.empty()) {
      if (optional) continue;  // not swept
      bad(a->flag, "no values");
    }
    if (a->values.size() > kMaxTrials / n)
      n = kMaxTrials + 1;  // saturate, then complain
    else
      n *= a->values.size();
    if (n > kMaxTrials)
      bad("--m/--kappa/--gamma/--zeta/--dt/--factor/--kd/--rayleigh-mass/--rayleigh-stiffness",
          "the grid has more than 4294967295 trials, too many for one sweep (use smaller "
          "ranges)");
  }
  trials_ = n;
}

SweepGrid::Index SweepGrid::index(std::uint64_t t) const {
  Index ix{};
  ix.kappa = t % spec_.kappa.values.size();
  t /= spec_.kappa.values.size();
  ix.m = t % spec_.m.values.size();
  t /= spec_.m.values.size();
  ix.gamma = t % spec_.gamma.values.size();
  t /= spec_.gamma.values.size();
  ix.factor = t % spec_.factor.values.size();
  t /= spec_.factor.values.size();
  ix.dt = t % spec_.dt.values.size();
  t /= spec_.dt.values.size();
  // SPEC 10's axes vary slowest, so that a sweep without them numbers its trials as before.
  for (auto [axis, at] : {std::pair{&spec_.kd, &ix.kd}, {&spec_.rayleigh_mass, &ix.rayleigh_mass},
                          {&spec_.rayleigh_stiffness, &ix.rayleigh_stiffness}}) {
    if (axis->values.empty()) continue;
    *at = t % axis->values.size();
    t /= axis->values.size();
  }
  return ix;
}

TrialParams SweepGrid::params(std::uint64_t t) const {
  const Index ix = index(t);
  TrialParams p;
  p.m = spec_.m.values[ix.m].value();
  p.kappa = spec_.kappa.values[ix.kappa].value();
  p.dt = spec_.dt.values[ix.dt].value();
  p.factor = spec_.factor.values[ix.factor].value();
  const double g = spec_.gamma.values[ix.gamma].value();
  p.gamma = spec_.gamma_mode == GammaMode::zeta ? g * lower_bound(p.m, p.kappa) : g;
  if (!spec_.kd.values.empty()) p.kd = spec_.kd.values[ix.kd].value();
  if (!spec_.rayleigh_mass.values.empty())
    p.rayleigh_mass = spec_.rayleigh_mass.values[ix.rayleigh_mass].value();
  if (!spec_.rayleigh_stiffness.values.empty())
    p.rayleigh_stiffness = spec_.rayleigh_stiffness.values[ix.rayleigh_stiffness].value();
  return p;
}

double SweepGrid::zeta(std::uint64_t t) const {
  const Index ix = index(t);
  if (spec_.gamma_mode == GammaMode::zeta) return spec_.gamma.values[ix.gamma].value();
  const TrialParams p = params(t);
  return p.gamma / lower_bound(p.m, p.kappa);
}

std::optional<std::string> similarity_unavailable(const SceneSpec& scene, bool kd_swept) {
  const ModelSpec& m = scene.model;
  // SPEC 10: a uniform kd enters the trajectory as kd/m, which trials of one class (equal
  // kappa/m and gamma/m at other m) share only when kd is in the class key (swept); alpha and
  // beta enter as themselves.
  if (scene.params.kd != 0 && !kd_swept)
    return "the dashpots (kd) are not scaled with m across the trials (kd/m differs; give --kd "
           "to make them an axis)";
  for (size_t i = 0; i < m.external_force.size(); ++i)
    if (m.external_force[i] != Vec3::Zero())
      return "node " + std::to_string(i) + " has an external force";
  auto uniform = [](const std::vector<double>& v) {
    for (double x : v)
      if (x != v.front()) return false;
    return true;
  };
  if (!uniform(m.mass_scale)) return "the masses are not uniform (mass_scale)";
  if (!uniform(m.gamma_scale)) return "the damping is not uniform (gamma_scale)";
  std::vector<double> stiffness;
  for (double a : m.anchor_scale)
    if (a > 0) stiffness.push_back(a);
  for (const Spring& s : m.springs) stiffness.push_back(s.kappa_scale);
  if (!stiffness.empty() && !uniform(stiffness))
    return "the stiffness is not uniform (kappa_scale / anchor scale)";
  if (kd_swept) {
    std::vector<double> dashpots;
    for (size_t i = 0; i < m.anchor_scale.size(); ++i)
      if (m.anchor_scale[i] > 0)
        dashpots.push_back(m.anchor_kd_scale.empty() ? 1.0 : m.anchor_kd_scale[i]);
    for (const Spring& s : m.springs) dashpots.push_back(s.kd_scale);
    if (!dashpots.empty() && !uniform(dashpots))
      return "the dashpots are not uniform (kd_scale)";
  }
  return std::nullopt;
}

namespace {

struct ClassKey {
  std::int64_t a, b, c, g, dt, factor, d, alpha, beta;
  bool operator==(const ClassKey& o) const {
    return a == o.a && b == o.b && c == o.c && g == o.g && dt == o.dt && factor == o.factor &&
           d == o.d && alpha == o.alpha && beta == o.beta;
  }
};

struct ClassKeyHash {
  size_t operator()(const ClassKey& k) const {
    std::uint64_t h = 1469598103934665603ull;
    for (std::int64_t v : {k.a, k.b, k.c, k.g, k.dt, k.factor, k.d, k.alpha, k.beta}) {
      h ^= static_cast<std::uint64_t>(v);
      h *= 1099511628211ull;
      h ^= h >> 29;
    }
    return static_cast<size_t>(h);
  }
};

/// Index of the first value equal to each value: equal decimals share an id.
std::vector<std::int64_t> value_ids(const Axis& axis) {
  std::vector<std::int64_t> ids(axis.values.size());
  for (size_t i = 0; i < ids.size(); ++i) {
    ids[i] = static_cast<std::int64_t>(i);
    for (size_t j = 0; j < i; ++j)
      if (axis.values[j] == axis.values[i]) {
        ids[i] = ids[j];
        break;
      }
  }
  return ids;
}

/// The axis values as integers on the quantum 10^-scale; false when one does not fit.
bool integers(const Axis& axis, int scale, std::vector<std::int64_t>& out) {
  out.clear();
  for (const Decimal& d : axis.values) {
    std::int64_t x = d.digits;
    if (!times_ten_pow(x, scale - d.scale)) return false;
    out.push_back(x);
  }
  return true;
}

}  // namespace

TrialClasses find_classes(const SweepGrid& grid, const std::optional<std::string>& scene_reason) {
  const SweepSpec& s = grid.spec();
  TrialClasses tc;
  const std::uint64_t n = grid.trials();
  tc.reason = !s.allow_similarity ? "turned off (--no-similarity)" : scene_reason.value_or("");
  const bool uses_gamma = uses_user_gamma(s.policy);
  const bool absolute = s.gamma_mode == GammaMode::absolute && uses_gamma;
  int scale = 0;
  const bool kd = !s.kd.values.empty();
  for (const Axis* a : {&s.m, &s.kappa, &s.kd})
    for (const Decimal& d : a->values) scale = std::max(scale, d.scale);
  if (absolute)
    for (const Decimal& d : s.gamma.values) scale = std::max(scale, d.scale);
  std::vector<std::int64_t> ia, ib, ic, id;
  if (tc.reason.empty() && (!integers(s.m, scale, ia) || !integers(s.kappa, scale, ib) ||
                            (absolute && !integers(s.gamma, scale, ic)) ||
                            (kd && !integers(s.kd, scale, id))))
    tc.reason = "the values have too many digits for exact integer classes";
  tc.class_of.resize(n);
  if (!tc.reason.empty()) {
    tc.representative.resize(n);
    for (std::uint64_t t = 0; t < n; ++t) {
      tc.class_of[t] = static_cast<std::uint32_t>(t);
      tc.representative[t] = t;
    }
    return tc;
  }
  tc.similarity = true;
  const std::vector<std::int64_t> gid = value_ids(s.gamma), did = value_ids(s.dt),
                                  fid = value_ids(s.factor), alpha = value_ids(s.rayleigh_mass),
                                  beta = value_ids(s.rayleigh_stiffness);
  std::unordered_map<ClassKey, std::uint32_t, ClassKeyHash> classes;
  classes.reserve(static_cast<size_t>(std::min<std::uint64_t>(n, 1u << 24)));
  for (std::uint64_t t = 0; t < n; ++t) {
    const SweepGrid::Index ix = grid.index(t);
    ClassKey k{ia[ix.m],
               ib[ix.kappa],
               absolute ? ic[ix.gamma] : 0,
               uses_gamma && !absolute ? gid[ix.gamma] : -1,
               did[ix.dt],
               s.policy == DampingPolicy::upper ? fid[ix.factor] : -1,
               kd ? id[ix.kd] : 0,
               alpha.empty() ? -1 : alpha[ix.rayleigh_mass],
               beta.empty() ? -1 : beta[ix.rayleigh_stiffness]};
    // kappa/m = b/a, gamma/m = c/a and kd/m = d/a: proportional tuples are one class (SPEC 6,
    // 10); alpha and beta enter the trajectory as themselves.
    const std::int64_t g = std::gcd(std::gcd(std::gcd(k.a, k.b), k.c), k.d);
    k.a /= g;
    k.b /= g;
    k.c /= g;
    k.d /= g;
    auto [it, inserted] = classes.try_emplace(k, static_cast<std::uint32_t>(tc.count()));
    if (inserted) tc.representative.push_back(t);
    tc.class_of[t] = it->second;
  }
  return tc;
}

std::uint64_t class_memory_bound(std::uint64_t trials) {
  // class_of (4) + representative (8) + hash map node and bucket (~80) + result (~64) +
  // formatted numbers while writing (~80) per trial, at most one class per trial.
  return trials * 236 + (64u << 20);
}

}  // namespace dampbound
