// A whole sweep: the CSV of an interrupted and resumed run equals that of one run; a journal
// left behind is refused without --resume; a finished sweep resumes to nothing.
#include "core/sweep/runner.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
#include <fstream>
#include <iterator>

#include "dampbound/physics/error.hpp"
#include "tests/core/sweep/sweep_test_util.hpp"

namespace dampbound {
namespace {

std::string bytes(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

bool file_exists(const std::string& p) {
  return std::ifstream(p).good();
}

SweepRequest request(const std::string& output) {
  SweepRequest rq;
  rq.scene = test::shipped_scene("two-node");
  rq.scene_text = bytes(rq.scene.path);
  rq.spec = test::small_sweep(rq.scene, 150);
  rq.output = output;
  rq.threads = 2;
  std::remove(output.c_str());
  std::remove((output + ".journal").c_str());
  return rq;
}

TEST(SweepRunner, OneRunWritesEveryTrial) {
  const SweepRequest rq = request(::testing::TempDir() + "runner_once.csv");
  const SweepReport rep = run_sweep(rq);
  EXPECT_FALSE(rep.cancelled);
  EXPECT_TRUE(rep.batched);
  EXPECT_EQ(rep.trials, 8u);
  EXPECT_EQ(rep.rows.size(), 8u);
  EXPECT_EQ(rep.classes_run, rep.classes);
  std::uint64_t counted = 0;
  for (std::uint64_t n : rep.outcome_trials) counted += n;
  EXPECT_EQ(counted, 8u);
  const SweepTable t = read_sweep_csv(rq.output);
  EXPECT_EQ(t.header.sweep_id, rep.header.sweep_id);
  ASSERT_EQ(t.rows.size(), rep.rows.size());
  for (size_t k = 0; k < t.rows.size(); ++k) {
    EXPECT_EQ(t.rows[k].trial, rep.rows[k].trial);
    EXPECT_EQ(t.rows[k].outcome, rep.rows[k].outcome);
    EXPECT_EQ(t.rows[k].iterations, rep.rows[k].iterations);
  }
  EXPECT_FALSE(file_exists(rq.output + ".journal"));
}

TEST(SweepRunner, ResumedRunWritesTheSameCsv) {
  SweepRequest whole = request(::testing::TempDir() + "runner_whole.csv");
  run_sweep(whole);
  SweepRequest rq = request(::testing::TempDir() + "runner_resumed.csv");
  const std::atomic<bool> cancel{true};
  rq.cancel = &cancel;
  const SweepReport cut = run_sweep(rq);
  EXPECT_TRUE(cut.cancelled);
  EXPECT_FALSE(file_exists(rq.output));
  EXPECT_THROW(run_sweep(rq), InputError);  // the journal exists: --resume is needed
  rq.cancel = nullptr;
  rq.resume = true;
  const SweepReport done = run_sweep(rq);
  EXPECT_FALSE(done.cancelled);
  EXPECT_EQ(done.earlier_runs, 1);
  EXPECT_EQ(bytes(rq.output), bytes(whole.output));
  // Nothing left to do: the finished CSV is read back.
  const SweepReport again = run_sweep(rq);
  EXPECT_TRUE(again.already_complete);
  EXPECT_EQ(again.rows.size(), done.rows.size());
}

TEST(SweepRunner, PlainRunEqualsBatchedCsvAndShardsCoverTheGrid) {
  SweepRequest batched = request(::testing::TempDir() + "runner_batched.csv");
  run_sweep(batched);
  SweepRequest plain = request(::testing::TempDir() + "runner_plain.csv");
  plain.use_kernel = false;
  const SweepReport rep = run_sweep(plain);
  EXPECT_FALSE(rep.batched);
  EXPECT_EQ(rep.plain_reason, "--plain");
  EXPECT_EQ(bytes(plain.output), bytes(batched.output));
  std::uint64_t rows = 0;
  for (int k = 1; k <= 2; ++k) {
    SweepRequest part = request(::testing::TempDir() + "runner_part" + std::to_string(k) + ".csv");
    part.shard = k;
    part.shards = 2;
    rows += run_sweep(part).rows.size();
  }
  EXPECT_EQ(rows, 8u);
}

TEST(SweepRunner, CpuSecondsGrow) {
  const double a = process_cpu_seconds();
  volatile double x = 0;
  for (int k = 0; k < 2000000; ++k) x = x + 1e-9 * k;
  EXPECT_GE(process_cpu_seconds(), a);
}

}  // namespace
}  // namespace dampbound
