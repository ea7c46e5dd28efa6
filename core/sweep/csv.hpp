#pragma once
// Sweep results as CSV: '#' metadata lines (which sweep, which part of it), a column line,
// one row per trial in trial order. Parts of a sharded sweep are merged back into exactly
// the file an unsharded run writes.
#include <cstdint>
#include <cstdio>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/sweep/grid.hpp"

namespace dampbound {

/// The metadata of a sweep CSV.
struct SweepHeader {
  std::string sweep_id;    ///< 16 hex digits: hash of the scene file and the definition
  std::string scene_path;  ///< the scene file (absolute when known)
  std::string scene_name;
  std::string definition;  ///< the axes, policy and protocol in words
  /// The damping policy of the definition: set by the runner, parsed once from "policy=" in
  /// the definition when a CSV is read back (nullopt when it names none this build knows).
  std::optional<DampingPolicy> policy;
  std::uint64_t trials = 0;
  std::uint64_t classes = 0;
  std::string similarity;  ///< "on" or "off (reason)"
  int shard = 1, shards = 1;
  /// The verdict rule (SPEC 8). A settled sweep says "rule=settled" in its definition and
  /// has three more columns; a first-entry sweep is written exactly as before the rule existed.
  StopRule rule = StopRule::first_entry;
  /// SPEC 10: the sweep has a kd, rayleigh_mass or rayleigh_stiffness axis, and three more
  /// columns after factor. A sweep without them is written exactly as before they existed.
  bool damping = false;
};

/// The column line (without newline): first-entry sweeps end at zero_length_springs; settled
/// sweeps add first_entry, left_at, settled_at (0 = none); with `damping`, kd,
/// rayleigh_mass, rayleigh_stiffness follow factor.
std::string sweep_csv_columns(StopRule rule = StopRule::first_entry, bool damping = false);

/// Writes the '#' lines and the column line.
void write_sweep_header(std::FILE* out, const SweepHeader& h);

/// A sweep CSV read back: the header and, per row, the fields the map and merge need.
struct SweepRow {
  std::uint64_t trial = 0;
  double m = 0, kappa = 0, gamma = 0, zeta = 0, dt = 0, factor = 0;
  double kd = 0, rayleigh_mass = 0, rayleigh_stiffness = 0;  ///< SPEC 10 (0 where not swept)
  Outcome outcome = Outcome::running;
  int iterations = 0;
  double max_displacement = 0;
  long long unstabilisable = 0;  ///< node-steps with gamma_lo > gamma_hi (the paper's check)
  int first_entry = 0;  ///< SPEC 8; under first-entry: the restore's iteration, else 0
  int left_at = 0;      ///< settled sweeps only
  int settled_at = 0;   ///< settled sweeps only
};

/// Builds the row of every trial whose class is in `shard` of `shards` (class % shards ==
/// shard - 1), in trial order, and hands it to `visit` with the trial's grid index, its class
/// and the class's result (`class_results[c]`: the result of class c's representative). The
/// one place rows are made from a grid: the CSV writer and sweep_rows() both use it.
using SweepRowVisitor = std::function<void(const SweepRow& row, const SweepGrid::Index& index,
                                           std::uint32_t cls, const TrialResult& result)>;
void for_each_sweep_row(const SweepGrid& grid, const TrialClasses& classes,
                        const std::vector<TrialResult>& class_results, int shard, int shards,
                        const SweepRowVisitor& visit);

/// Writes the rows of for_each_sweep_row as CSV lines.
void write_sweep_rows(std::FILE* out, const SweepGrid& grid, const TrialClasses& classes,
                      const std::vector<TrialResult>& class_results, int shard, int shards);

struct SweepTable {
  SweepHeader header;
  std::vector<SweepRow> rows;
  std::vector<std::string> lines;  ///< the raw row lines (only when asked for)
};

/// Reads a sweep CSV. Throws InputError naming the file and line for anything malformed.
SweepTable read_sweep_csv(const std::string& path, bool keep_lines = false);

/// Joins the parts of a sharded sweep into `out` (written atomically). Throws InputError
/// when the parts belong to different sweeps, miss or repeat a part, or do not cover every
/// trial exactly once.
void merge_sweep_parts(const std::vector<std::string>& parts, const std::string& out);

/// 64-bit FNV-1a of bytes, as 16 hex digits.
std::string fnv1a_hex(const std::string& bytes);

}  // namespace dampbound
