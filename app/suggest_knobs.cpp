#include "app/suggest_knobs.hpp"

#include <cmath>
#include <cstdio>
#include <algorithm>
#include <cstdlib>
#include <future>
#include <string>
#include <thread>
#include <vector>

#include "core/analysis/damping_limits.hpp"
#include "core/analysis/kappa_ceiling.hpp"
#include "core/analysis/linear_stability_cholesky.hpp"
#include "core/io/files.hpp"
#include "core/io/format.hpp"
#include "core/io/report.hpp"
#include "core/io/vtu.hpp"
#include "dampbound/physics/error.hpp"
#include "dampbound/physics/step.hpp"

namespace dampbound::app {

RayleighPlotter& rayleigh_plotter() {
  static RayleighPlotter plotter = nullptr;
  return plotter;
}

namespace {

/// The verdict, and the largest displacement at the end against the band's reference (the
/// pull): below 1 the run did not grow, whether or not it settled (zero modes, which no spring
/// resists at rest, keep a linear-regime run from settling).
std::string run_text(const VerifiedRun& r) {
  return std::string(r.verified() ? "settles" : "does not settle") + " (" +
         verdict_text(r.result, r.rules) + "; max |x-X| at the end " +
         format_digits(r.result.max_displacement / r.rules.reference, 3) + "x the pull)";
}

void print_ceiling(const StiffnessCeiling& c) {
  std::printf("  %-28s %5d springs %5d anchors  ", c.label.c_str(), c.springs, c.anchors);
  if (std::isinf(c.factor)) {
    std::printf("no ceiling: none of them acts on a free node\n");
    return;
  }
  if (c.factor <= 0) {
    std::printf("unstable even without them (index %s >= 4 at factor 1)\n",
                format_human(c.index).c_str());
    return;
  }
  std::printf("factor < %s (index %s at factor 1)\n", format_human(c.factor).c_str(),
              format_human(c.index).c_str());
  if (c.ran)
    std::printf("  %-28s runs (perturbation x%s, the linear regime): at 0.98x %s; at 1.02x %s\n",
                "", format_digits(c.run_scale, 3).c_str(), run_text(c.below).c_str(),
                run_text(c.above).c_str());
}

/// "Z" or "Z1,Z2"; "F1:F2".
void parse_ratios(const std::string& text, RayleighRequest& r) {
  const auto number = [&](const std::string& s, const char* flag) {
    char* end = nullptr;
    const double v = c_strtod(s.c_str(), &end);
    if (s.empty() || *end != '\0' || !std::isfinite(v))
      throw InputError(std::string(flag) + ": '" + printable(s) + "' is not a number");
    return v;
  };
  const size_t comma = text.find(',');
  r.zeta1 = number(text.substr(0, comma), "--rayleigh");
  r.zeta2 = comma == std::string::npos ? r.zeta1 : number(text.substr(comma + 1), "--rayleigh");
}

void parse_band(const std::string& text, RayleighRequest& r) {
  const size_t colon = text.find(':');
  if (colon == std::string::npos) throw InputError("--band: give F1:F2 in Hz (got '" + printable(text) + "')");
  const auto number = [&](const std::string& s) {
    char* end = nullptr;
    const double v = c_strtod(s.c_str(), &end);
    if (s.empty() || *end != '\0' || !std::isfinite(v) || !(v > 0))
      throw InputError("--band: '" + printable(s) + "' is not a frequency > 0 (Hz)");
    return v;
  };
  r.f1 = number(text.substr(0, colon));
  r.f2 = number(text.substr(colon + 1));
  if (!(r.f2 > r.f1)) throw InputError("--band: needs F1 < F2 (got '" + printable(text) + "')");
}

}  // namespace

int print_kappa_max(const SceneSpec& scene, const Params& p, const StopRules& rules, bool verify,
                    const std::string& vtu, double max_factor_flops) {
  if (!vtu.empty()) check_writable(vtu);
  std::printf("stiffness ceiling at dt = %s s with the scene's damping (SPEC 10's exact index at "
              "rest; beta K follows the stiffness; stable below the factor)\n",
              format_human(p.dt).c_str());
  std::vector<StiffnessSelection> selections = {whole_selection(scene.model)};
  for (const SceneRegion& r : scene.regions) selections.push_back(region_selection(scene.model, r));
  if (scene.regions.empty()) std::printf("  (the scene has no [[region]] or [[mesh_region]])\n");
  int status = 0;
  const Model model = compile_model(scene.model, p);
  bool damped = model.spring_damping;
  for (size_t i = 0; i < model.gamma.size(); ++i) damped = damped || model.gamma[i] > 0;
  if (!damped)
    std::printf("  (no damping: below the factor the step is marginally stable, no growth and no "
                "decay, so no run settles)\n");
  for (const StiffnessSelection& s : selections) {
    const StiffnessCeiling c = stiffness_ceiling(scene, p, s, rules, verify, {}, max_factor_flops);
    print_ceiling(c);
    if (c.ran && !c.below.verified()) status = 1;
  }
  const ContactCeilings k = contact_ceilings(model, model.spec().rest, p.dt, p.kd, 5);
  std::printf("contact ceiling per node: one zero-length spring to a fixed point (dashpot kd = %s) "
              "keeping the node's SPEC 9/10 rows dominant, k < 2 (gamma_safe_i - gamma_i - kd) / "
              "(dt + 2 beta)\n",
              format_human(p.kd).c_str());
  if (k.worst.empty()) {
    std::printf("  no free node\n");
  } else {
    std::printf("  min %s, median %s (mass unit/s^2)%s\n", format_human(k.min).c_str(),
                format_human(k.median).c_str(),
                k.zero > 0 ? ("; " + std::to_string(k.zero) +
                              " nodes have no margin left (rows not dominant without contact)")
                                 .c_str()
                           : "");
    std::printf("     node  k_max        mass       kappa_i    position (cm)\n");
    for (int i : k.worst) {
      const size_t u = static_cast<size_t>(i);
      const Vec3& x = model.spec().rest[u];
      std::printf("  %7d  %-12s %-10s %-10s (%s, %s, %s)\n", i, format_human(k.k_max[u]).c_str(),
                  format_digits(model.mass[u], 4).c_str(),
                  format_digits(model.node_kappa[u], 4).c_str(), format_digits(x.x(), 4).c_str(),
                  format_digits(x.y(), 4).c_str(), format_digits(x.z(), 4).c_str());
    }
  }
  if (!vtu.empty()) {
    const State rest = rest_state(model);
    StepWorkspace ws;
    write_file_atomic(vtu, [&](std::ostream& out) {
      write_vtu(out, model, rest, ws, p.dt, scene.body, {{"contact_stiffness_max", k.k_max}});
    });
    std::printf("wrote %s (point array contact_stiffness_max; NaN at fixed nodes)\n", vtu.c_str());
  }
  return status;
}

int print_rayleigh(const SceneSpec& scene, const Params& p, const std::string& ratios,
                   const std::string& band, const std::string& plot, double max_factor_flops) {
  RayleighRequest request;
  parse_ratios(ratios, request);
  if (!band.empty()) parse_band(band, request);
  if (!plot.empty()) {
    if (!rayleigh_plotter())
      throw InputError("--plot: this dampbound is built without the headless EGL host");
    check_writable(plot);
  }
  const RayleighDesign d = rayleigh_from_spectrum(scene, p, request, {}, max_factor_flops);
  std::printf("Rayleigh damping from the spectrum of M^-1 K at rest: lowest mode %s Hz, highest "
              "%s Hz; a step of %s s resolves up to 1/(2 dt) = %s Hz\n",
              format_human(d.f_lowest).c_str(), format_human(d.f_highest).c_str(),
              format_human(p.dt).c_str(), format_human(d.f_nyquist).c_str());
  std::printf("  asked      zeta %s at %s Hz and zeta %s at %s Hz\n", format_human(d.zeta1).c_str(),
              format_human(d.f1).c_str(), format_human(d.zeta2).c_str(), format_human(d.f2).c_str());
  std::printf("  pair       rayleigh_mass (alpha) = %s 1/s, rayleigh_stiffness (beta) = %s s\n",
              format_human(d.alpha).c_str(), format_human(d.beta).c_str());
  if (!d.feasible) {
    std::printf("no Rayleigh pair gives these ratios: %s would be negative (zeta(f) = alpha/(4 pi "
                "f) + beta pi f cannot fall faster than 1/f or rise faster than f)\n",
                d.alpha < 0 ? "alpha" : "beta");
    return 1;
  }
  std::printf("  at dt      the scene's gamma and kd held, alpha as above: stable for beta < %s s "
              "(exact index)",
              format_human(d.beta_max).c_str());
  if (!std::isnan(d.beta_max_closed))
    std::printf("; SPEC 10's closed form %s s%s", format_human(d.beta_max_closed).c_str(),
                d.beta_max_closed <= 0 ? " (none)" : "");
  std::printf("\n");
  if (d.stable) {
    std::printf("  verdict    stable at dt = %s s; the exact dt limit with the pair is %s s\n",
                format_human(p.dt).c_str(), format_human(d.dt_max).c_str());
  } else if (!(d.beta_max > 0)) {
    std::printf("  verdict    NOT stable: no beta >= 0 is, with this alpha and the scene's gamma and "
                "kd at dt = %s s; the exact dt limit with the pair is %s s\n",
                format_human(p.dt).c_str(), format_human(d.dt_max).c_str());
  } else {
    std::printf("  verdict    NOT stable: beta = %s s is above what the step allows; the largest "
                "stable beta is %s s, which reaches zeta %s at %s Hz (%s at the highest mode); "
                "the exact dt limit with the pair is %s s\n",
                format_human(d.beta).c_str(), format_human(d.beta_max).c_str(),
                format_human(d.zeta2_at_beta_max).c_str(), format_human(d.f2).c_str(),
                format_human(d.zeta_highest_at_beta_max).c_str(), format_human(d.dt_max).c_str());
  }
  std::printf("  zeta(f)    f (Hz)       zeta\n");
  for (size_t k = 0; k < d.curve_f.size(); k += 5) {
    const double f = d.curve_f[k];
    std::printf("             %-12s %-12s %s\n", format_human(f).c_str(),
                format_human(d.curve_zeta[k]).c_str(),
                f < d.f_lowest ? "below the lowest mode" : f > d.f_highest ? "above the highest mode" : "");
  }
  std::printf("             %-12s %-12s lowest mode\n             %-12s %-12s highest mode\n",
              format_human(d.f_lowest).c_str(),
              format_human(rayleigh_zeta(d.alpha, d.beta, d.f_lowest)).c_str(),
              format_human(d.f_highest).c_str(),
              format_human(rayleigh_zeta(d.alpha, d.beta, d.f_highest)).c_str());
  if (d.forced_nodes > 0)
    std::printf("  load       %d nodes carry external forces: the mass term alone lets node %d "
                "fall no faster than |f|/(alpha m) = %s cm/s (%s cm/s with its gamma_i too)\n",
                d.forced_nodes, d.terminal_node, format_human(d.terminal_velocity).c_str(),
                format_human(d.terminal_velocity_with_gamma).c_str());
  std::printf("  scene keys [params] rayleigh_mass = %s, rayleigh_stiffness = %s\n",
              format_number(d.alpha).c_str(), format_number(d.beta).c_str());
  if (!plot.empty()) {
    const std::string renderer = rayleigh_plotter()(d, plot);
    std::printf("wrote %s (%s)\n", plot.c_str(), renderer.c_str());
  }
  return d.stable ? 0 : 1;
}

/// SPEC 10: the exact stable range of each damping kind at this dt, the others held, and a
/// run at the middle of each range (the settled rule judges: stable is not settled in time).
/// The kinds' searches share one pattern analysis where their index matrices share a pattern
/// (SharedFactors); the runs, each its own Session, run side by side, at most one per
/// hardware thread, and the lines come in the kinds' order once all are done.
void print_damping_kinds(const SceneSpec& scene, const Params& p, const StopRules& rules,
                         bool verify, double max_factor_flops) {
  std::printf("damping kinds at dt = %s s, each with the others held (the exact limit, "
              "at rest)\n",
              format_human(p.dt).c_str());
  struct Kind {
    DampingKind kind;
    double max = 0;
    std::string over;  ///< the budget's refusal, where one factorisation is over it
    std::future<VerifiedRun> run;
  };
  std::vector<Kind> kinds;
  for (DampingKind kind : {DampingKind::nodal, DampingKind::dashpot, DampingKind::rayleigh_mass,
                           DampingKind::rayleigh_stiffness})
    kinds.push_back({kind, 0, {}, {}});
  SharedFactors shared;
  for (Kind& k : kinds) {
    try {
      k.max = damping_kind_max(scene.model, scene.model.rest, p, k.kind, max_factor_flops, &shared);
    } catch (const FactorisationOverBudget& over) {
      k.over = over.what();
    }
  }
  // The runs: a thread each, started while fewer than the hardware's threads run.
  const size_t lanes = std::max(1u, std::thread::hardware_concurrency());
  std::vector<Kind*> queue;
  for (Kind& k : kinds)
    if (verify && k.over.empty() && k.max > 0 && !std::isinf(k.max)) queue.push_back(&k);
  for (size_t first = 0; first < queue.size(); first += lanes) {
    const size_t last = std::min(queue.size(), first + lanes);
    for (size_t q = first; q < last; ++q) {
      Params run = p;
      coefficient(run, queue[q]->kind) = queue[q]->max / 2;
      queue[q]->run = std::async(std::launch::async,
                                 [&scene, run, &rules] { return verify_run(scene, run, rules, ""); });
    }
    for (size_t q = first; q < last; ++q) queue[q]->run.wait();
  }
  for (Kind& k : kinds) {
    Params now = p;
    const double value = coefficient(now, k.kind);
    if (!k.over.empty()) {
      std::printf("  %-19s now %-10s not computed: %s (--factor-budget)\n", to_string(k.kind),
                  format_human(value).c_str(), k.over.c_str());
      continue;
    }
    std::printf("  %-19s now %-10s stable for %s in [0, %s)", to_string(k.kind),
                format_human(value).c_str(), to_string(k.kind),
                std::isinf(k.max) ? "inf" : format_human(k.max).c_str());
    if (k.max <= 0) {
      std::printf(": no value is stable with the others held\n");
      continue;
    }
    if (!k.run.valid()) {
      std::printf("\n");
      continue;
    }
    const VerifiedRun mid = k.run.get();
    std::printf("; run at %s: %s\n", format_human(k.max / 2).c_str(),
                verdict_text(mid.result, mid.rules).c_str());
  }
}

}  // namespace dampbound::app
