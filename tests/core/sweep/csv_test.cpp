// Sweep CSVs: what is written reads back as the same rows; forged or broken files are refused.
#include "core/sweep/csv.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "core/sweep/setup.hpp"
#include "core/sweep/trials.hpp"
#include "dampbound/physics/error.hpp"
#include "tests/core/sweep/sweep_test_util.hpp"

namespace dampbound {
namespace {

std::string temp_path(const std::string& name) {
  return ::testing::TempDir() + "dampbound_csv_test_" + name;
}

std::string write_file(const std::string& name, const std::string& text) {
  const std::string p = temp_path(name);
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

struct Written {
  SweepGrid grid;
  TrialClasses classes;
  std::vector<TrialResult> results;
  SweepHeader header;
};

Written write_small(const std::string& path, StopRule rule, int shard = 1, int shards = 1) {
  const SceneSpec scene = test::shipped_scene("two-node");
  SweepSpec s = test::small_sweep(scene);
  s.rules.rule = rule;
  Written w{SweepGrid(s), {}, {}, {}};
  w.classes = find_classes(w.grid, similarity_unavailable(scene));
  std::vector<TrialParams> reps;
  for (std::uint64_t t : w.classes.representative) reps.push_back(w.grid.params(t));
  w.results = run_batched(scene, s.policy, s.rules, reps);
  w.header.sweep_id = "0123456789abcdef";
  w.header.scene_name = "two-node";
  w.header.definition = sweep_definition(s);
  w.header.trials = w.grid.trials();
  w.header.classes = w.classes.count();
  w.header.similarity = "on";
  w.header.shard = shard;
  w.header.shards = shards;
  w.header.rule = rule;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  write_sweep_header(f, w.header);
  write_sweep_rows(f, w.grid, w.classes, w.results, shard, shards);
  std::fclose(f);
  return w;
}

TEST(SweepCsv, RoundTripGivesTheRowsOfTheRun) {
  for (StopRule rule : {StopRule::first_entry, StopRule::settled}) {
    SCOPED_TRACE(to_string(rule));
    const std::string path = temp_path("roundtrip.csv");
    const Written w = write_small(path, rule);
    const SweepTable t = read_sweep_csv(path, true);
    EXPECT_EQ(t.header.sweep_id, w.header.sweep_id);
    EXPECT_EQ(t.header.definition, w.header.definition);
    EXPECT_EQ(t.header.trials, w.grid.trials());
    EXPECT_EQ(t.header.classes, w.classes.count());
    EXPECT_EQ(t.header.rule, rule);
    EXPECT_EQ(t.header.policy, DampingPolicy::fixed);  // parsed once, from the definition
    const std::vector<SweepRow> mem = sweep_rows(w.grid, w.classes, w.results, 1, 1);
    ASSERT_EQ(t.rows.size(), mem.size());
    ASSERT_EQ(t.lines.size(), mem.size());
    for (size_t k = 0; k < mem.size(); ++k) {
      EXPECT_EQ(t.rows[k].trial, mem[k].trial);
      EXPECT_EQ(t.rows[k].m, mem[k].m);
      EXPECT_EQ(t.rows[k].kappa, mem[k].kappa);
      EXPECT_DOUBLE_EQ(t.rows[k].gamma, mem[k].gamma);
      EXPECT_DOUBLE_EQ(t.rows[k].zeta, mem[k].zeta);
      EXPECT_EQ(t.rows[k].dt, mem[k].dt);
      EXPECT_EQ(t.rows[k].outcome, mem[k].outcome);
      EXPECT_EQ(t.rows[k].iterations, mem[k].iterations);
      EXPECT_EQ(t.rows[k].unstabilisable, mem[k].unstabilisable);
      EXPECT_EQ(t.rows[k].first_entry, mem[k].first_entry);
      if (rule == StopRule::settled) {
        EXPECT_EQ(t.rows[k].left_at, mem[k].left_at);
        EXPECT_EQ(t.rows[k].settled_at, mem[k].settled_at);
      }
    }
  }
}

TEST(SweepCsv, ShardsMergeIntoTheUnshardedFile) {
  const std::string whole = temp_path("whole.csv"), p1 = temp_path("p1.csv"),
                    p2 = temp_path("p2.csv"), merged = temp_path("merged.csv");
  write_small(whole, StopRule::first_entry);
  write_small(p1, StopRule::first_entry, 1, 2);
  write_small(p2, StopRule::first_entry, 2, 2);
  merge_sweep_parts({p2, p1}, merged);
  auto bytes = [](const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  EXPECT_EQ(bytes(merged), bytes(whole));
  EXPECT_THROW(merge_sweep_parts({p1, p1}, merged), InputError);  // a part repeated
  EXPECT_THROW(merge_sweep_parts({p1}, merged), InputError);      // a part missing
}

TEST(SweepCsv, ANumberThatIsNotWholeIsRefusedNamingItsColumn) {
  const std::string good = temp_path("numbers.csv");
  write_small(good, StopRule::first_entry);
  std::ifstream in(good, std::ios::binary);
  const std::string text(std::istreambuf_iterator<char>(in), {});
  // The first row (after the column line), with field k replaced.
  const size_t row = text.find('\n', text.find("trial,m,")) + 1;
  const size_t row_end = text.find('\n', row);
  auto with_field = [&](int k, const std::string& value) {
    std::string line = text.substr(row, row_end - row);
    size_t a = 0;
    for (int i = 0; i < k; ++i) a = line.find(',', a) + 1;
    const size_t b = line.find(',', a);
    line.replace(a, b - a, value);
    return text.substr(0, row) + line + text.substr(row_end);
  };
  auto message = [&](const std::string& name, int k, const std::string& value) {
    try {
      read_sweep_csv(write_file(name, with_field(k, value)));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(read without an error)");
  };
  EXPECT_NO_THROW(read_sweep_csv(write_file("numbers-same.csv", with_field(1, "0.001"))));
  EXPECT_NO_THROW(read_sweep_csv(write_file("numbers-inf.csv", with_field(12, "inf"))));
  EXPECT_NE(message("m.csv", 1, "abc").find("m.csv:"), std::string::npos);
  EXPECT_NE(message("m.csv", 1, "abc").find("bad number 'abc' in column m"), std::string::npos);
  EXPECT_NE(message("dt.csv", 5, "0.05x").find("in column dt"), std::string::npos);
  EXPECT_NE(message("empty.csv", 2, "").find("bad number '' in column kappa"), std::string::npos);
  EXPECT_NE(message("it.csv", 11, "12.5").find("bad integer '12.5' in column iterations"),
            std::string::npos);
  EXPECT_NE(message("neg.csv", 14, "-3").find("in column unstabilisable"), std::string::npos);
  EXPECT_NE(message("disp.csv", 12, "1.5.2").find("in column max_displacement"),
            std::string::npos);
}

TEST(SweepCsv, ForgedOrBrokenFilesAreRefused) {
  const std::string good = temp_path("good.csv");
  write_small(good, StopRule::first_entry);
  std::ifstream in(good, std::ios::binary);
  const std::string text(std::istreambuf_iterator<char>(in), {});
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    const size_t p = t.find(from);
    EXPECT_NE(p, std::string::npos) << from;
    return t.replace(p, from.size(), to);
  };
  EXPECT_NO_THROW(read_sweep_csv(write_file("same.csv", text)));
  EXPECT_THROW(read_sweep_csv(write_file("magic.csv", replaced("sweep v1", "sweep v9"))),
               InputError);
  EXPECT_THROW(read_sweep_csv(write_file("shard.csv", replaced("# shard: 1/1", "# shard: 3/2"))),
               InputError);
  EXPECT_THROW(
      read_sweep_csv(write_file("count.csv", replaced("# trials: 8", "# trials: 99999999999"))),
      InputError);
  EXPECT_THROW(read_sweep_csv(write_file("columns.csv", replaced("trial,m,", "trial,mass,"))),
               InputError);
  EXPECT_THROW(read_sweep_csv(write_file("outcome.csv", replaced(",restored,", ",bogus,"))),
               InputError);
  EXPECT_THROW(read_sweep_csv(write_file("cut.csv", text.substr(0, text.find("trial,m,")))),
               InputError);
  EXPECT_THROW(read_sweep_csv(temp_path("no-such-file.csv")), InputError);
  // A policy this build does not know is read as none (no prediction checks), not refused.
  EXPECT_EQ(read_sweep_csv(write_file("upper.csv", replaced("policy=fixed", "policy=upper")))
                .header.policy,
            DampingPolicy::upper);
  EXPECT_EQ(read_sweep_csv(write_file("nopolicy.csv", replaced("policy=fixed", "policy=sticky")))
                .header.policy,
            std::nullopt);
}

TEST(SweepCsv, ColumnsAndHash) {
  const std::string first = sweep_csv_columns(StopRule::first_entry);
  const std::string settled = sweep_csv_columns(StopRule::settled);
  EXPECT_EQ(settled.rfind(first, 0), 0u);
  EXPECT_EQ(settled.substr(first.size()), ",first_entry,left_at,settled_at");
  // Pinned: sweep ids in existing CSVs and journals depend on these bytes. The offset basis
  // in csv.cpp is 1469598103934665603, one digit short of FNV-1a's 14695981039346656037, so
  // these are not standard FNV-1a values; changing it would change every sweep id.
  EXPECT_EQ(fnv1a_hex(""), "14650fb0739d0383");
  EXPECT_EQ(fnv1a_hex("a"), "44bd8ad473cd9906");
  EXPECT_NE(fnv1a_hex("a"), fnv1a_hex("b"));
}

}  // namespace
}  // namespace dampbound
