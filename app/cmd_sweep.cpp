// dampbound sweep [SCENE]: the paper's experiment at scale (SPEC 5, 6): every combination of
// m, kappa, gamma (or zeta), dt and factor, one CSV row per trial. docs/sweeps.md.
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>

#include "app/commands.hpp"
#include "app/map_png.hpp"
#include "app/options.hpp"
#include "app/sweep_rule.hpp"
#include "core/io/files.hpp"
#include "core/io/format.hpp"
#include "core/physics/damping_ratio.hpp"
#include "core/physics/integrate.hpp"
#include "core/run/settle_proof.hpp"
#include "core/sweep/map.hpp"
#include "core/sweep/progress.hpp"
#include "core/sweep/runner.hpp"
#include "core/sweep/safe_edge.hpp"
#include "core/sweep/summary.hpp"
#include "dampbound/physics/error.hpp"
#include "gpu/gpu_sweep.hpp"

namespace dampbound::app::cmd_sweep {
namespace {

std::atomic<bool> g_interrupted{false};

/// The output's lock, <output>.lock, held (flock) for the whole run: a second sweep on the same
/// output, resumed or not, is refused while the first holds it. The kernel lets go when the
/// process ends, killed or not (a killed sweep leaves the empty file, which the next takes).
class OutputLock {
 public:
  explicit OutputLock(const std::string& output) : path_(output + ".lock") {
    fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw InputError("-o: cannot create the lock file " + path_);
    // Locked, and still the file at that path (a sweep ending unlinks it, see below).
    struct stat at {}, held {};
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0 || ::stat(path_.c_str(), &at) != 0 ||
        ::fstat(fd_, &held) != 0 || at.st_ino != held.st_ino || at.st_dev != held.st_dev) {
      ::close(fd_);
      throw InputError("-o: another dampbound sweep is writing " + output + " (it holds " + path_ +
                       "); wait for it to finish or stop it, then run again (--resume continues it)");
    }
  }
  /// Removed while still held, so a sweep leaves no file beside its output.
  ~OutputLock() {
    ::unlink(path_.c_str());
    ::close(fd_);
  }
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

 private:
  std::string path_;
  int fd_ = -1;
};

extern "C" void on_interrupt(int) {
  g_interrupted.store(true);
  // A second Ctrl-C kills at once; the journal still holds everything synced so far.
  ::signal(SIGINT, SIG_DFL);
  ::signal(SIGTERM, SIG_DFL);
}

struct SweepArgs {
  std::string scene = "paper-plane";
  std::string preset, m, kappa, zeta, gamma, dt, factor, policy, output, shard = "1/1", map;
  std::string kd, rayleigh_mass, rayleigh_stiffness;  // SPEC 10 axes
  std::string progress = "auto";
  std::string device = "cpu";  // --device: cpu, gpu, auto (gpu/gpu_sweep.hpp)
  double progress_interval = 10, sync_interval = 1;
  int max_iter = 0, threads = 0;
  std::string rule;  // empty: first-entry for a paper preset, else the default (settled)
  bool resume = false, no_similarity = false, plain = false, no_early_stop = false;
  CLI::Option *max_iter_opt = nullptr, *m_opt = nullptr, *kappa_opt = nullptr, *zeta_opt = nullptr,
              *gamma_opt = nullptr, *dt_opt = nullptr, *factor_opt = nullptr, *policy_opt = nullptr,
              *kd_opt = nullptr, *rayleigh_mass_opt = nullptr, *rayleigh_stiffness_opt = nullptr;
};

/// The sweep's definition: preset, then flags, then the scene's own values.
SweepSpec make_spec(const SweepArgs& a, const SceneSpec& scene) {
  std::string m = format_number(scene.params.m), kappa = format_number(scene.params.kappa);
  std::string gamma = format_number(scene.params.gamma), zeta;
  if (scene.params.zeta) zeta = format_number(*scene.params.zeta);  // the scene's [params] zeta
  std::string dt = format_number(scene.params.dt), factor = format_number(scene.params.factor);
  DampingPolicy policy = scene.params.policy;
  StopRules rules = scene.rules;
  if (a.preset == "paper-lower" || a.preset == "paper-upper") {
    m = kappa = "0.0001:0.1:0.0001";
    dt = "0.05";
    if (a.preset == "paper-lower") {
      zeta = "0.25,0.5,1";
      policy = DampingPolicy::fixed;
      factor = "1";
      rules.max_iterations = 1000;
    } else {
      policy = DampingPolicy::upper;
      factor = "1,1.05";
      rules.max_iterations = 10000;
    }
  } else if (!a.preset.empty()) {
    throw InputError("--preset: unknown preset '" + a.preset + "' (paper-lower, paper-upper)");
  }
  auto given = [](const CLI::Option* o) { return o && o->count() > 0; };
  if (given(a.m_opt)) m = a.m;
  if (given(a.kappa_opt)) kappa = a.kappa;
  bool use_zeta = !zeta.empty();
  if (given(a.zeta_opt)) {
    zeta = a.zeta;
    use_zeta = true;
  }
  if (given(a.gamma_opt)) {
    gamma = a.gamma;
    use_zeta = false;
  }
  if (given(a.dt_opt)) dt = a.dt;
  if (given(a.factor_opt)) factor = a.factor;
  if (given(a.policy_opt)) policy = *parse_policy(a.policy);
  if (given(a.max_iter_opt)) rules.max_iterations = a.max_iter;
  // SPEC 8: the paper's presets reproduce it under its rule, named here; anything else is
  // judged by the default rule unless --rule says otherwise.
  if (!a.rule.empty())
    rules.rule = stop_rule_of(a.rule);
  else if (!a.preset.empty())
    rules.rule = StopRule::first_entry;

  SweepSpec s;
  s.m = parse_axis("--m", m, AxisDomain::positive);
  s.kappa = parse_axis("--kappa", kappa, AxisDomain::positive);
  s.gamma_mode = use_zeta ? GammaMode::zeta : GammaMode::absolute;
  s.gamma = use_zeta ? parse_axis("--zeta", zeta, AxisDomain::non_negative)
                     : parse_axis("--gamma", gamma, AxisDomain::non_negative);
  s.dt = parse_axis("--dt", dt, AxisDomain::positive);
  s.factor = parse_axis("--factor", factor, AxisDomain::non_negative);
  // SPEC 10: with any of its damping given (by a flag or the scene), all three are axes, the
  // scene's value where no flag is given, so that every row says its damping.
  const std::pair<const CLI::Option*, double> damping[3] = {
      {a.kd_opt, scene.params.kd},
      {a.rayleigh_mass_opt, scene.params.rayleigh_mass},
      {a.rayleigh_stiffness_opt, scene.params.rayleigh_stiffness}};
  bool any = false;
  for (const auto& [opt, value] : damping) any = any || given(opt) || value != 0;
  if (any) {
    s.kd = parse_axis("--kd", given(a.kd_opt) ? a.kd : format_number(scene.params.kd),
                      AxisDomain::non_negative);
    s.rayleigh_mass = parse_axis(
        "--rayleigh-mass",
        given(a.rayleigh_mass_opt) ? a.rayleigh_mass : format_number(scene.params.rayleigh_mass),
        AxisDomain::non_negative);
    s.rayleigh_stiffness = parse_axis("--rayleigh-stiffness",
                                      given(a.rayleigh_stiffness_opt)
                                          ? a.rayleigh_stiffness
                                          : format_number(scene.params.rayleigh_stiffness),
                                      AxisDomain::non_negative);
  }
  s.policy = policy;
  s.rules = rules;
  s.allow_similarity = !a.no_similarity;
  return s;
}

int run(const SweepArgs& a) {
  if (a.no_early_stop) set_settle_proof_enabled(false);
  SceneSpec scene = load_scene_arg(a.scene);
  SweepRequest rq;
  rq.scene_text = sweep_identity_text(read_file_text(scene.path), scene);
  rq.spec = make_spec(a, scene);
  // Each trial's gamma is zeta * 2 sqrt(m kappa) in zeta mode: with the scales of resolve_zeta()
  // that is gamma_i = zeta * 2 sqrt(m_i kappa_i) at every node, as run and bounds give it.
  if (rq.spec.gamma_mode == GammaMode::zeta && !scene.params.zeta) scene.params.zeta = 1;
  if (rq.spec.gamma_mode != GammaMode::zeta) scene.params.zeta.reset();
  resolve_zeta(scene.model, scene.params);
  parse_shard(a.shard, rq.shard, rq.shards);
  auto writable = [](const std::string& flag, const std::string& path) {
    try {
      check_writable(path);
    } catch (const InputError& e) {
      throw InputError(flag + ": " + e.what());
    }
  };
  writable("-o", a.output);
  if (!a.map.empty()) {
    if (!map_png_available())
      throw InputError("--map: this build has no headless EGL host (DAMPBOUND_EGL=OFF)");
    writable("--map", a.map);
  }
  rq.scene = std::move(scene);
  rq.output = a.output;
  rq.resume = a.resume;
  rq.threads = a.threads;
  rq.use_kernel = !a.plain;
  rq.sync_interval_s = a.sync_interval;
  rq.cancel = &g_interrupted;
  const bool terminal = a.progress == "bar" || (a.progress == "auto" && ::isatty(2));
  auto printer = std::make_shared<ProgressPrinter>(stderr, terminal, a.progress_interval);
  // SPEC 8: once the sweep runs (its inputs accepted), which rule, and the other's cost.
  const std::string intro = rule_intro(rq.spec.rules.rule, rq.spec.rules.max_iterations);
  auto said = std::make_shared<bool>(false);
  if (a.progress != "none")
    rq.progress = [printer, intro, said](const SweepProgress& p) {
      if (!*said) std::fprintf(stderr, "dampbound: sweep: %s\n", intro.c_str());
      *said = true;
      printer->update(p);
    };

  struct sigaction sa {};
  sa.sa_handler = on_interrupt;
  ::sigaction(SIGINT, &sa, nullptr);
  ::sigaction(SIGTERM, &sa, nullptr);
  const std::unique_ptr<TrialDevice> device =
      choose_sweep_device(*parse_sweep_device(a.device), rq.scene, rq.spec.policy, rq.spec.rules,
                          a.plain, stderr);
  rq.device = device.get();
  const OutputLock lock(a.output);
  const SweepReport rep = run_sweep(rq);
  ::signal(SIGINT, SIG_DFL);
  ::signal(SIGTERM, SIG_DFL);

  if (rep.cancelled) {
    std::fprintf(stderr,
                 "dampbound: interrupted: %llu of %llu classes are done and kept in %s.journal; "
                 "run the same command with --resume to finish\n",
                 static_cast<unsigned long long>(rep.classes_resumed + rep.classes_run),
                 static_cast<unsigned long long>(rep.classes), a.output.c_str());
    return 130;
  }
  const SweepHeader& h = rep.header;
  std::printf("sweep        %s (%s), sweep id %s, part %d/%d\n", h.scene_name.c_str(),
              h.definition.c_str(), h.sweep_id.c_str(), h.shard, h.shards);
  if (rep.already_complete) {
    std::printf("complete     %s already holds this sweep; nothing to do\n", a.output.c_str());
  } else {
    std::printf(
        "trials       %llu in %llu classes (similarity %s); %llu classes run now, %llu "
        "from the journal\n",
        static_cast<unsigned long long>(rep.trials), static_cast<unsigned long long>(rep.classes),
        h.similarity.c_str(), static_cast<unsigned long long>(rep.classes_run),
        static_cast<unsigned long long>(rep.classes_resumed));
    // Rates over this run's work (trials from the journal were stepped by an earlier run).
    const double s = std::max(rep.seconds, 1e-9);
    std::printf(
        "time         %.1f s (%.1f s of CPU)%s, %.0f trials/s, %.3g trial-steps/s, %.3g "
        "spring evaluations/s (%s)\n",
        rep.seconds, rep.cpu_seconds, rep.classes_resumed > 0 ? " this run" : "",
        static_cast<double>(rep.trials - rep.trials_resumed) / s,
        static_cast<double>(rep.lane_steps) / s,
        static_cast<double>(rep.lane_steps) * static_cast<double>(rep.spring_evaluations_per_step) /
            s,
        !rep.device.empty() ? ("GPU " + rep.device).c_str()
        : rep.batched       ? "batched kernel"
                            : ("Session per trial: " + rep.plain_reason).c_str());
    if (rep.classes_resumed > 0) {
      if (rep.untimed_classes == 0)
        std::printf("in all       %.1f s (%.1f s of CPU) over %d runs\n",
                    rep.seconds + rep.earlier_seconds, rep.cpu_seconds + rep.earlier_cpu_seconds,
                    rep.earlier_runs + 1);
      else
        std::printf(
            "in all       more than %.1f s (%.1f s of CPU): the time of %llu of the "
            "journal's classes was not recorded (an older dampbound records none)\n",
            rep.seconds + rep.earlier_seconds, rep.cpu_seconds + rep.earlier_cpu_seconds,
            static_cast<unsigned long long>(rep.untimed_classes));
    }
  }
  if (!rep.already_complete)
    if (const auto cost = rule_cost_line(rep.rows, rq.spec.rules.rule, rep.seconds))
      std::printf("%s\n", cost->c_str());
  std::printf("output       %s\n", a.output.c_str());
  double lambda_unit = NAN;
  try {
    lambda_unit = unit_stiffness_eigenvalue(rq.scene);
  } catch (const std::exception& e) {
    std::printf("warning      no lambda_max for the exact linear limit: %s\n", e.what());
  }
  const DampingPolicy policy = rq.spec.policy;
  for (const std::string& line :
       summary_lines(rep.rows, policy, lambda_unit, dashpot_stiffness_ratio(rq.scene)))
    std::printf("%s\n", line.c_str());
  // SPEC 9: the safe check against the outcomes (fixed), what the safe policy promised (safe).
  for (const std::string& line :
       safe_summary_lines(rep.rows, policy, unit_safe_bound(rq.scene), lambda_unit))
    std::printf("%s\n", line.c_str());
  if (!integrator_traits(rq.scene.params.integrator).paper_step)
    std::printf(
        "note         the scene steps %s: linear limit and bound above "
        "are derived for the paper's semi-implicit step; their lines count how often "
        "they held here, they guarantee nothing\n",
        to_string(rq.scene.params.integrator));
  if (!a.map.empty()) {
    SweepTable table;
    table.header = h;
    table.rows = rep.rows;
    render_map_png(build_stability_map(table, lambda_unit), a.map);
    std::printf("map          %s\n", a.map.c_str());
  }
  return 0;
}

std::function<int()> setup(CLI::App& root) {
  auto a = std::make_shared<SweepArgs>();
  CLI::App* cmd = root.add_subcommand(
      "sweep",
      "Run the paper's protocol over a grid of m, kappa, gamma (or zeta), dt, factor and the "
      "dashpot and Rayleigh damping; one CSV row per trial. Trials sharing kappa/m, gamma/m, "
      "kd/m, the Rayleigh coefficients and dt run once.");
  cmd->add_option("scene", a->scene, "scene file or shipped scene name (default paper-plane)");
  cmd->add_option("--preset", a->preset,
                  "paper-lower (m, kappa 0.0001..0.1 step 0.0001, zeta 0.25,0.5,1, "
                  "1000 iterations) or paper-upper (policy upper, factor 1,1.05, 10000 "
                  "iterations); other flags override it");
  a->m_opt = cmd->add_option("--m", a->m, "masses: A:B:STEP and/or a comma list (mass unit)");
  a->kappa_opt =
      cmd->add_option("--kappa", a->kappa, "stiffnesses: A:B:STEP and/or a list (mass unit/s^2)");
  auto* z = a->zeta_opt = cmd->add_option(
      "--zeta", a->zeta, "gamma as fractions of the lower bound 2 sqrt(m kappa): a list");
  auto* g = a->gamma_opt =
      cmd->add_option("--gamma", a->gamma, "absolute gamma: A:B:STEP and/or a list");
  z->excludes(g);
  a->dt_opt = cmd->add_option("--dt", a->dt, "time steps (s): a list");
  a->factor_opt =
      cmd->add_option("--factor", a->factor, "factors of the upper bound (policy upper): a list");
  a->kd_opt = cmd->add_option("--kd", a->kd,
                              "dashpots along the springs (mass unit/s): A:B:STEP and/or "
                              "a list");
  a->rayleigh_mass_opt = cmd->add_option("--rayleigh-mass", a->rayleigh_mass,
                                         "Rayleigh alpha (1/s): A:B:STEP and/or a list");
  a->rayleigh_stiffness_opt =
      cmd->add_option("--rayleigh-stiffness", a->rayleigh_stiffness,
                      "Rayleigh beta (s): A:B:STEP and/or a list");
  a->policy_opt = cmd->add_option("--policy", a->policy, "damping policy: fixed, clamp, upper, lower (the paper's), safe (the safe bound)")
                      ->check(CLI::IsMember(policy_names()));
  a->max_iter_opt = cmd->add_option("--max-iter", a->max_iter, "iteration limit of the protocol")
                        ->check(whole_range(1, 100000000));
  cmd->add_option("-o,--output", a->output, "the results CSV (written atomically at the end)")
      ->required();
  cmd->add_option("--threads", a->threads, "worker threads (default: one per CPU)")
      ->check(whole_range(1, 1024));
  cmd->add_flag("--resume", a->resume, "finish an interrupted sweep from OUTPUT.journal");
  cmd->add_option("--shard", a->shard, "run part K of N (classes c with c % N == K-1)");
  cmd->add_option("--map", a->map, "also draw the stability map into this PNG");
  add_rule_option(cmd, a->rule,
                  "default: settled; first-entry, the paper's, with --preset paper-lower/upper");
  cmd->add_flag("--no-similarity", a->no_similarity, "run every trial, even equivalent ones");
  cmd->add_flag("--no-early-stop", a->no_early_stop,
                "settled rule: step every trial to its limit, without SPEC 8's proof "
                "(docs/settled.md); to check the proof or time it");
  cmd->add_flag("--plain", a->plain, "step each trial with Session (the plain step()), no SIMD");
  cmd->add_option("--device", a->device,
                  "cpu (default), gpu (exit 2 without a usable GPU), auto (the GPU when one can "
                  "run the sweep, else the CPU; says which on stderr)")
      ->check(CLI::IsMember({"cpu", "gpu", "auto"}));
  cmd->add_option("--progress", a->progress,
                  "auto (bar on a terminal, else lines), bar, lines, none")
      ->check(CLI::IsMember({"auto", "bar", "lines", "none"}));
  cmd->add_option("--progress-interval", a->progress_interval,
                  "seconds between progress lines when not on a terminal (default 10)")
      ->check(number_range(0.0, 86400.0));
  cmd->add_option("--sync-interval", a->sync_interval,
                  "seconds between fsyncs of the journal of finished classes (default 1)")
      ->check(number_range(0.0, 3600.0));
  return [a] { return run(*a); };
}

const bool registered = register_command("sweep", setup);

}  // namespace
}  // namespace dampbound::app::cmd_sweep
