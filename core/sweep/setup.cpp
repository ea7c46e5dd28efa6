// The parts of a sweep decided before any trial runs: shard, resources, identity, rows.
#include <sys/statvfs.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "core/io/format.hpp"
#include "core/run/settle_proof.hpp"
#include "core/sweep/runner.hpp"
#include "core/sweep/setup.hpp"
#include "dampbound/physics/error.hpp"

namespace dampbound {

namespace {

std::string gigabytes(double bytes) {
  char buf[32];
  c_snprintf(buf, sizeof buf, "%.2f GB", bytes / 1e9);
  return buf;
}

/// MemAvailable of /proc/meminfo in bytes; 0 when unknown.
double available_memory() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kb = 0;
  std::string unit;
  while (in >> key >> kb >> unit)
    if (key == "MemAvailable:") return kb * 1024;
  return 0;
}

}  // namespace

void parse_shard(const std::string& text, int& shard, int& shards) {
  int k = 0, n = 0;
  char extra = 0;
  // At most 9 digits each: %d of a longer number overflows (3/99999999999 would wrap).
  if (std::sscanf(text.c_str(), "%9d/%9d%c", &k, &n, &extra) != 2 || n < 1 || k < 1 || k > n)
    throw InputError("--shard: '" + printable(text) +
                     "' must be K/N with 1 <= K <= N <= 999999999 (part K of N)");
  shard = k;
  shards = n;
}

void check_sweep_resources(const SweepGrid& grid, const std::string& output, int shards) {
  const double trials = static_cast<double>(grid.trials());
  const double part = trials / shards;
  // Memory: the classes of the whole grid, plus the rows of this part for the summary.
  const double memory = static_cast<double>(class_memory_bound(grid.trials())) +
                        part * static_cast<double>(sizeof(SweepRow));
  const double avail = available_memory();
  if (avail > 0 && memory > avail)
    throw InputError("--m/--kappa/--gamma/--zeta/--dt/--factor: the grid has " +
                     std::to_string(grid.trials()) + " trials and needs about " +
                     gigabytes(memory) + " of memory, but only " + gigabytes(avail) +
                     " is available; use smaller ranges or --shard");
  // Disk: the CSV (about 170 bytes a row) and the journal (about 60 bytes a class).
  const double disk = part * 170 + part * 60;
  const auto slash = output.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "." : output.substr(0, slash + 1);
  struct statvfs fs {};
  if (::statvfs(dir.c_str(), &fs) == 0) {
    const double free_bytes = static_cast<double>(fs.f_bavail) * static_cast<double>(fs.f_frsize);
    if (disk > free_bytes)
      throw InputError("-o: " + output + " would need about " + gigabytes(disk) + " of disk for " +
                       std::to_string(grid.trials()) + " trials, but only " +
                       gigabytes(free_bytes) + " is free");
  }
}

std::string sweep_id(const std::string& scene_text, const std::string& definition) {
  return fnv1a_hex(fnv1a_hex(scene_text) + "\n" + definition);
}

std::string sweep_identity_text(const std::string& scene_file_text, const SceneSpec& scene) {
  if (scene.grid) return scene_file_text;  // all of it is in the file's text
  const ModelSpec& m = scene.model;
  std::string bytes;
  auto add = [&](const void* p, size_t n) { bytes.append(static_cast<const char*>(p), n); };
  for (const Vec3& x : m.rest) add(x.data(), 3 * sizeof(double));
  for (const Vec3& f : m.external_force) add(f.data(), 3 * sizeof(double));
  add(m.mass_scale.data(), m.mass_scale.size() * sizeof(double));
  add(m.gamma_scale.data(), m.gamma_scale.size() * sizeof(double));
  add(m.anchor_scale.data(), m.anchor_scale.size() * sizeof(double));
  add(m.fixed.data(), m.fixed.size());
  for (const Spring& sp : m.springs) {
    add(&sp.i, sizeof sp.i);
    add(&sp.j, sizeof sp.j);
    add(&sp.rest_length, sizeof sp.rest_length);
    add(&sp.kappa_scale, sizeof sp.kappa_scale);
  }
  return scene_file_text + "\nmodel " + fnv1a_hex(bytes);
}

std::string sweep_definition(const SweepSpec& s) {
  std::string d = "m=" + s.m.spec + " kappa=" + s.kappa.spec;
  d += (s.gamma_mode == GammaMode::zeta ? " zeta=" : " gamma=") + s.gamma.spec;
  d += " dt=" + s.dt.spec + " policy=" + to_string(s.policy) + " factor=" + s.factor.spec;
  // SPEC 10's axes, said only when swept, so that a sweep without them keeps its id and bytes.
  if (!s.kd.values.empty()) d += " kd=" + s.kd.spec;
  if (!s.rayleigh_mass.values.empty()) d += " rayleigh-mass=" + s.rayleigh_mass.spec;
  if (!s.rayleigh_stiffness.values.empty()) d += " rayleigh-stiffness=" + s.rayleigh_stiffness.spec;
  d += " max-iter=" + std::to_string(s.rules.max_iterations);
  d += " reference=" + format_number(s.rules.reference) +
       " restore-fraction=" + format_number(s.rules.restore_fraction) +
       " diverge-factor=" + format_number(s.rules.diverge_factor);
  d += s.allow_similarity ? " similarity=auto" : " similarity=off";
  // SPEC 8; said only when settled, so that a first-entry sweep keeps its id and bytes.
  if (s.rules.rule == StopRule::settled) {
    d += " rule=settled";
    // Every settled trial stepped to its limit (sweep --no-early-stop): other iterations and
    // counts in the CSV, so another sweep.
    if (!settle_proof_enabled()) d += " early-stop=off";
  }
  return d;
}

std::vector<SweepRow> sweep_rows(const SweepGrid& grid, const TrialClasses& classes,
                                 const std::vector<TrialResult>& class_results, int shard,
                                 int shards) {
  std::vector<SweepRow> rows;
  for_each_sweep_row(grid, classes, class_results, shard, shards,
                     [&](const SweepRow& r, const SweepGrid::Index&, std::uint32_t,
                         const TrialResult&) { rows.push_back(r); });
  return rows;
}

}  // namespace dampbound
