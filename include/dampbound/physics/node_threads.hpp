#pragma once
// Threads for the per-node loops of step(): a small persistent pool that splits [0, n) into
// contiguous chunks, one per thread. Every loop it runs writes disjoint per-node outputs or
// per-chunk partial results that the caller combines exactly (integer counts, max), so a
// step gives the same bits on any number of threads.
#include "dampbound/physics/export.hpp"
#include <cstddef>
#include <functional>
#include <memory>

namespace dampbound DAMPBOUND_API {

class NodeThreads {
 public:
  /// The default grain: below this many items per thread a loop runs on fewer threads (one
  /// for small models): waking a thread costs more than a few thousand springs of work
  /// (measured: a 1000-node block stepped 1.6x slower with its 5859 springs split in two).
  static constexpr std::size_t kMinItemsPerThread = 16384;

  NodeThreads();
  explicit NodeThreads(int threads);
  /// A copy has the same thread count and threads of its own, started when first needed.
  NodeThreads(const NodeThreads& other);
  NodeThreads& operator=(const NodeThreads& other);
  ~NodeThreads();

  /// 1 (the default) runs every loop on the caller's thread; 0 means one per hardware thread.
  void set_threads(int threads);
  int threads() const { return threads_; }
  /// The fewest items a chunk gets (kMinItemsPerThread unless set; tests split small loops).
  void set_grain(std::size_t items) { grain_ = items < 1 ? 1 : items; }
  /// How long a thread polls before it sleeps: the workers for the next loop after their
  /// chunk, the caller for the workers after its own (0, the default: they sleep at once).
  /// For back-to-back loops with little work between them, such as Lanczos's products, where
  /// waking a sleeping thread costs a good part of a loop (docs/performance.md).
  void set_spin_microseconds(int us);
  int spin_microseconds() const { return spin_us_; }

  /// How many chunks run(n, ...) splits n items into: between 1 and threads().
  int chunks(std::size_t n) const;

  /// Calls fn(chunk, begin, end) for the chunks(n) contiguous ranges covering [0, n), chunk 0
  /// on the calling thread, and returns when all are done. fn must not call run().
  void run(std::size_t n, const std::function<void(int, std::size_t, std::size_t)>& fn);

 private:
  struct Pool;
  int threads_ = 1;
  std::size_t grain_ = kMinItemsPerThread;
  int spin_us_ = 0;
  std::unique_ptr<Pool> pool_;
};

}  // namespace dampbound
