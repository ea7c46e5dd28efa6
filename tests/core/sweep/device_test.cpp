// sweep --device's names, and the runner's path through a TrialDevice: a device that runs
// the trial body's host copy (what the GPU runs per thread) writes the CPU's CSV bytes, whole,
// in shards, and interrupted then resumed.
#include "core/sweep/device.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
#include <fstream>
#include <iterator>

#include "core/sweep/flat_model.hpp"
#include "core/sweep/runner.hpp"
#include "tests/core/sweep/sweep_test_util.hpp"

namespace dampbound {
namespace {

std::string bytes(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// The trial body on the host, behind the TrialDevice interface; stops handing out results
/// after `stop_after` trials by setting `cancel` (an interrupted run).
class HostBodyDevice final : public TrialDevice {
 public:
  HostBodyDevice(const SweepRequest& rq, std::atomic<bool>* cancel = nullptr, int stop_after = -1)
      : flat_(rq.scene, rq.spec.policy, rq.spec.rules), cancel_(cancel), stop_after_(stop_after) {}
  std::string name() const override { return "host trial body"; }
  std::uint64_t run(const TrialSource& source, const TrialSink& sink,
                    const std::atomic<bool>* cancel) override {
    std::uint64_t steps = 0;
    std::size_t id = 0;
    TrialParams p;
    while (!(cancel && cancel->load()) && source(id, p)) {
      const TrialResult r = run_trial_body(flat_, {p})[0];
      steps += static_cast<std::uint64_t>(r.iterations);
      sink(id, r);
      if (cancel_ && --stop_after_ == 0) cancel_->store(true);
    }
    return steps;
  }

 private:
  FlatScene flat_;
  std::atomic<bool>* cancel_;
  int stop_after_;
};

SweepRequest request(const std::string& output, const char* scene = "paper-plane") {
  SweepRequest rq;
  rq.scene = test::shipped_scene(scene);
  rq.scene_text = bytes(rq.scene.path);
  rq.spec = test::small_sweep(rq.scene, 60);
  rq.spec.m = parse_axis("--m", "0.001,0.002,0.003", AxisDomain::positive);
  rq.output = ::testing::TempDir() + output;
  rq.threads = 2;
  std::remove(rq.output.c_str());
  std::remove((rq.output + ".journal").c_str());
  return rq;
}

TEST(SweepDevice, NamesRoundTrip) {
  for (SweepDevice d : {SweepDevice::cpu, SweepDevice::gpu, SweepDevice::automatic})
    EXPECT_EQ(parse_sweep_device(to_string(d)), d);
  EXPECT_EQ(std::string(to_string(SweepDevice::automatic)), "auto");
  EXPECT_FALSE(parse_sweep_device("tpu"));
  EXPECT_FALSE(parse_sweep_device(""));
}

TEST(SweepDevice, ADeviceWritesTheCpusBytes) {
  const SweepRequest cpu = request("device_cpu.csv");
  const SweepReport cpu_rep = run_sweep(cpu);
  EXPECT_TRUE(cpu_rep.device.empty());
  SweepRequest dev = request("device_body.csv");
  HostBodyDevice body(dev);
  dev.device = &body;
  const SweepReport rep = run_sweep(dev);
  EXPECT_EQ(rep.device, "host trial body");
  EXPECT_EQ(rep.classes_run, cpu_rep.classes_run);
  EXPECT_GT(rep.lane_steps, 0u);
  EXPECT_EQ(bytes(dev.output), bytes(cpu.output));
  // In shards too, and each shard is the CPU's shard.
  for (int k = 1; k <= 2; ++k) {
    SweepRequest c = request("device_cpu_part.csv");
    c.shard = k;
    c.shards = 2;
    run_sweep(c);
    SweepRequest d = request("device_body_part.csv");
    d.shard = k;
    d.shards = 2;
    HostBodyDevice part(d);
    d.device = &part;
    run_sweep(d);
    EXPECT_EQ(bytes(d.output), bytes(c.output)) << "shard " << k;
  }
}

TEST(SweepDevice, InterruptedAndResumedThroughADevice) {
  const SweepRequest cpu = request("device_whole.csv");
  run_sweep(cpu);
  SweepRequest rq = request("device_resumed.csv");
  std::atomic<bool> cancel{false};
  HostBodyDevice first(rq, &cancel, 5);
  rq.device = &first;
  rq.cancel = &cancel;
  const SweepReport cut = run_sweep(rq);
  EXPECT_TRUE(cut.cancelled);
  EXPECT_GT(cut.classes_run, 0u);
  EXPECT_LT(cut.classes_run, cut.classes);
  // The CPU finishes what the device began (the journal does not say which device ran).
  rq.device = nullptr;
  rq.cancel = nullptr;
  rq.resume = true;
  const SweepReport done = run_sweep(rq);
  EXPECT_FALSE(done.cancelled);
  EXPECT_EQ(done.classes_resumed, cut.classes_run);
  EXPECT_EQ(bytes(rq.output), bytes(cpu.output));
}

}  // namespace
}  // namespace dampbound
