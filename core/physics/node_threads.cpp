#include "dampbound/physics/node_threads.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

namespace dampbound {

/// Workers wait for a new generation, run their chunk of the current job and count down.
struct NodeThreads::Pool {
  std::vector<std::thread> workers;
  std::mutex mutex;
  std::condition_variable wake, done;
  const std::function<void(int, std::size_t, std::size_t)>* job = nullptr;
  std::size_t n = 0;
  int chunks = 0;
  std::atomic<int> pending{0};
  std::atomic<unsigned long> generation{0};
  bool stopping = false;
  const std::chrono::microseconds spin;

  Pool(int threads, int spin_us) : spin(spin_us) {
    try {
      for (int t = 1; t < threads; ++t) workers.emplace_back([this, t] { work(t); });
    } catch (const std::exception& e) {
      // No thread (an address-space or process limit): stop those started and say so, rather
      // than leave joinable threads to std::terminate or a loop waiting for them.
      const std::size_t failed = workers.size() + 1;
      stop();
      throw std::runtime_error("could not start worker thread " + std::to_string(failed) + " of " +
                               std::to_string(threads - 1) + ": " + e.what());
    }
  }

  ~Pool() { stop(); }

  void stop() {
    {
      std::lock_guard<std::mutex> lock(mutex);
      stopping = true;
    }
    wake.notify_all();
    for (std::thread& w : workers) w.join();
    workers.clear();
  }

  /// Polls `ready` for up to `spin` (none by default); the caller then takes the lock and
  /// waits as before, so polling only saves the sleep and the wake-up.
  template <class Ready>
  void poll(Ready ready) const {
    if (spin.count() == 0) return;
    const auto until = std::chrono::steady_clock::now() + spin;
    while (!ready() && std::chrono::steady_clock::now() < until) std::this_thread::yield();
  }

  static std::size_t begin_of(std::size_t n, int chunks, int c) {
    return n * static_cast<std::size_t>(c) / static_cast<std::size_t>(chunks);
  }

  void work(int t) {
    unsigned long seen = 0;
    for (;;) {
      poll([&] { return generation.load(std::memory_order_acquire) != seen; });
      std::unique_lock<std::mutex> lock(mutex);
      wake.wait(lock, [&] { return stopping || generation != seen; });
      if (stopping) return;
      seen = generation;
      if (t >= chunks) continue;  // this job needs fewer threads
      const auto* f = job;
      const std::size_t count = n;
      const int parts = chunks;
      lock.unlock();
      (*f)(t, begin_of(count, parts, t), begin_of(count, parts, t + 1));
      lock.lock();
      if (--pending == 0) done.notify_one();
    }
  }

  void run(std::size_t count, int parts,
           const std::function<void(int, std::size_t, std::size_t)>& fn) {
    {
      std::lock_guard<std::mutex> lock(mutex);
      job = &fn;
      n = count;
      chunks = parts;
      pending = parts - 1;
      ++generation;
    }
    wake.notify_all();
    fn(0, 0, begin_of(count, parts, 1));
    poll([&] { return pending.load(std::memory_order_acquire) == 0; });
    std::unique_lock<std::mutex> lock(mutex);
    done.wait(lock, [&] { return pending == 0; });
    job = nullptr;
  }
};

NodeThreads::NodeThreads() = default;
NodeThreads::NodeThreads(int threads) { set_threads(threads); }
NodeThreads::NodeThreads(const NodeThreads& other)
    : threads_(other.threads_), grain_(other.grain_), spin_us_(other.spin_us_) {}

NodeThreads& NodeThreads::operator=(const NodeThreads& other) {
  if (this != &other) {
    set_threads(other.threads_);
    grain_ = other.grain_;
    if (spin_us_ != other.spin_us_) set_spin_microseconds(other.spin_us_);
  }
  return *this;
}

NodeThreads::~NodeThreads() = default;

void NodeThreads::set_threads(int threads) {
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (threads == threads_) return;
  pool_.reset();
  threads_ = threads;
}

void NodeThreads::set_spin_microseconds(int us) {
  spin_us_ = us < 0 ? 0 : us;
  pool_.reset();  // the next loop starts threads that poll for as long
}

int NodeThreads::chunks(std::size_t n) const {
  const std::size_t by_size = std::max<std::size_t>(1, n / grain_);
  return static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(threads_), by_size));
}

void NodeThreads::run(std::size_t n,
                      const std::function<void(int, std::size_t, std::size_t)>& fn) {
  const int parts = chunks(n);
  if (parts <= 1) {
    fn(0, 0, n);
    return;
  }
  if (!pool_) pool_ = std::make_unique<Pool>(threads_, spin_us_);
  pool_->run(n, parts, fn);
}

}  // namespace dampbound
