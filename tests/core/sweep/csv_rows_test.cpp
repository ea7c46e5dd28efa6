// Sweep CSV rows checked against their header: an edited row under an intact header is
// refused, the rows a run wrote pass.
#include "core/sweep/csv_rows.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "core/sweep/setup.hpp"
#include "core/sweep/trials.hpp"
#include "dampbound/physics/error.hpp"
#include "tests/core/sweep/sweep_test_util.hpp"

namespace dampbound {
namespace {

std::string rows_temp_path(const std::string& name) {
  return ::testing::TempDir() + "dampbound_csv_rows_test_" + name;
}

std::string text_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// A small first-entry sweep of two-node where trials 0 and 3 (m = kappa) share a class.
void write_sweep(const std::string& path, int shard = 1, int shards = 1) {
  const SceneSpec scene = test::shipped_scene("two-node");
  SweepSpec s = test::small_sweep(scene);
  s.kappa = parse_axis("--kappa", "0.001,0.002", AxisDomain::positive);
  s.gamma = parse_axis("--zeta", "1", AxisDomain::non_negative);
  s.rules.rule = StopRule::first_entry;
  const SweepGrid grid(s);
  const TrialClasses classes = find_classes(grid, similarity_unavailable(scene));
  std::vector<TrialParams> reps;
  for (std::uint64_t t : classes.representative) reps.push_back(grid.params(t));
  const std::vector<TrialResult> results = run_batched(scene, s.policy, s.rules, reps);
  SweepHeader h;
  h.sweep_id = "0123456789abcdef";
  h.scene_name = "two-node";
  h.definition = sweep_definition(s);
  h.trials = grid.trials();
  h.classes = classes.count();
  h.similarity = "on";
  h.shard = shard, h.shards = shards;
  h.rule = s.rules.rule;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  write_sweep_header(f, h);
  write_sweep_rows(f, grid, classes, results, shard, shards);
  std::fclose(f);
}

/// The file at `path` with the row of `trial` passed through `edit` (its fields).
std::string edited(const std::string& path, int trial,
                   const std::function<void(std::vector<std::string>&)>& edit) {
  std::string text = text_of(path);
  const std::string head = "\n" + std::to_string(trial) + ",";
  const size_t start = text.find(head) + 1, end = text.find('\n', start);
  std::vector<std::string> f;
  std::string field;
  for (char c : text.substr(start, end - start) + ",") {
    if (c == ',') f.push_back(field), field.clear();
    else field += c;
  }
  edit(f);
  std::string line;
  for (const std::string& x : f) line += (line.empty() ? "" : ",") + x;
  const std::string out = rows_temp_path("edited.csv");
  std::ofstream(out, std::ios::binary) << text.substr(0, start) + line + text.substr(end);
  return out;
}

std::string refusal(const std::string& path) {
  try {
    check_sweep_rows(read_sweep_csv(path, true), path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SweepCsvRows, TheRowsARunWroteAreAccepted) {
  const std::string path = rows_temp_path("whole.csv");
  write_sweep(path);
  const SweepTable t = read_sweep_csv(path, true);
  ASSERT_EQ(t.rows.size(), 4u);
  EXPECT_EQ(t.header.classes, 3u);  // m = kappa twice: one class
  EXPECT_NO_THROW(check_sweep_rows(t, path));
  EXPECT_EQ(grid_of_header(t.header, path).trials(), 4u);
}

TEST(SweepCsvRows, AValueEditedUnderAnIntactHeaderIsRefusedNamingTrialAndColumn) {
  const std::string path = rows_temp_path("values.csv");
  write_sweep(path);
  EXPECT_NE(refusal(edited(path, 1, [](auto& f) { f[1] = "0.003"; })).find("trial 1: m is 0.003"),
            std::string::npos);
  EXPECT_NE(refusal(edited(path, 2, [](auto& f) { f[5] = "0.04"; })).find("trial 2: dt"),
            std::string::npos);
  EXPECT_NE(refusal(edited(path, 0, [](auto& f) { f[6] = "clamp"; })).find("policy 'clamp'"),
            std::string::npos);
}

TEST(SweepCsvRows, AResultEditedInOneTrialOfAClassIsRefused) {
  const std::string path = rows_temp_path("class.csv");
  write_sweep(path);
  // Trial 3 took trial 0's result (same class): its iterations edited.
  const std::string why =
      refusal(edited(path, 3, [](auto& f) { f[11] = std::to_string(std::stoi(f[11]) + 1); }));
  EXPECT_NE(why.find("trial 3: its result differs from trial 0's"), std::string::npos) << why;
  EXPECT_NE(refusal(edited(path, 3, [](auto& f) { f[9] = "1"; })).find("ran = 1"),
            std::string::npos);
}

TEST(SweepCsvRows, AnOutcomeThatContradictsTheBandIsRefused) {
  const std::string path = rows_temp_path("outcome.csv");
  write_sweep(path);
  const SweepTable t = read_sweep_csv(path, true);
  ASSERT_EQ(t.rows[1].outcome, Outcome::restored);
  // Restored with a displacement far outside the band, or not restored before the limit.
  EXPECT_NE(refusal(edited(path, 1, [](auto& f) { f[12] = "3"; })).find("contradicts the band"),
            std::string::npos);
  EXPECT_NE(refusal(edited(path, 1, [](auto& f) { f[10] = "not_restored"; }))
                .find("contradicts the band"),
            std::string::npos);
}

TEST(SweepCsvRows, MergeChecksTheRowsOfEveryPart) {
  const std::string p1 = rows_temp_path("p1.csv"), p2 = rows_temp_path("p2.csv"),
                    merged = rows_temp_path("merged.csv");
  write_sweep(p1, 1, 2);
  write_sweep(p2, 2, 2);
  EXPECT_NO_THROW(merge_sweep_parts({p1, p2}, merged));
  const SweepTable t = read_sweep_csv(p2, true);
  const std::string bad = edited(p2, static_cast<int>(t.rows[0].trial), [](auto& f) { f[2] = "0.005"; });
  std::filesystem::remove(merged);
  EXPECT_THROW(merge_sweep_parts({p1, bad}, merged), InputError);
  EXPECT_FALSE(std::filesystem::exists(merged));
}

}  // namespace
}  // namespace dampbound
