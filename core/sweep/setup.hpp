#pragma once
// What a sweep settles before its first trial (the shard, the resources it needs, its identity)
// and, at the end, the rows of its CSV from the class results.
#include <string>
#include <vector>

#include "core/sweep/csv.hpp"
#include "core/sweep/grid.hpp"
#include "core/sweep/kernel.hpp"
#include "dampbound/run/scene.hpp"

namespace dampbound {

/// "K/N" -> (K, N), 1 <= K <= N. Throws InputError naming --shard.
void parse_shard(const std::string& text, int& shard, int& shards);

/// Checks, before any work, that the grid's classes fit in memory and its CSV and journal on
/// the output's disk. Throws InputError naming the flags.
void check_sweep_resources(const SweepGrid& grid, const std::string& output, int shards);

/// The sweep's identity: hash of the scene bytes and the definition (16 hex digits).
std::string sweep_id(const std::string& scene_text, const std::string& definition);

/// What a sweep's identity takes from its scene: the scene file's bytes and, for a scene whose
/// geometry comes from another file (a [mesh]: no generated grid), a digest of the model as
/// loaded, so that a changed mesh file gives another sweep id and --resume and merge refuse the
/// old journal or part.
std::string sweep_identity_text(const std::string& scene_file_text, const SceneSpec& scene);

/// The definition in words, as in the CSV header.
std::string sweep_definition(const SweepSpec& spec);

/// Rows of the trials of `shard` of `shards` in trial order, from the class results.
std::vector<SweepRow> sweep_rows(const SweepGrid& grid, const TrialClasses& classes,
                                 const std::vector<TrialResult>& class_results, int shard,
                                 int shards);

}  // namespace dampbound
