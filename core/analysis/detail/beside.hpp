#pragma once
// Work on the core that a serial phase leaves idle: one thread beside the caller's, and the
// Lanczos estimate on the other threads while it runs. certified_largest_eigenvalue prepares
// its factorisations beside its estimate, and certified_spectrum makes the bottom end's
// estimate beside the top end's factorisations (linear_stability_cholesky.cpp). Lanczos gives
// the same bits on any thread count, so the results are those of one thread.
#include <atomic>
#include <exception>
#include <functional>
#include <thread>

#include "core/analysis/detail/lanczos.hpp"

namespace dampbound::detail {

/// The threads a `threads` argument asks for: 0 is one per CPU.
int resolved_threads(int threads);

/// Work on a thread of its own beside the caller's: done() once it has returned or thrown;
/// finish() joins it and throws what it threw. The destructor joins it too (when something
/// else threw first).
class Beside {
 public:
  explicit Beside(std::function<void()> work);
  Beside(const Beside&) = delete;
  Beside& operator=(const Beside&) = delete;
  ~Beside();
  bool done() const { return done_.load(std::memory_order_acquire); }
  /// After done(): whether it threw.
  bool failed() const { return error_ != nullptr; }
  void finish();

 private:
  std::atomic<bool> done_{false};
  std::exception_ptr error_;
  std::thread thread_;  // last: it starts once the members above exist
};

/// The Lanczos estimate of S while a thread is busy beside it: on cores - 1 threads, then on
/// all of them once `beside_done()` says so; stopped at the next step when `stop()` says so.
TopEstimate estimate_beside(const SparseMatrix& S, int cores,
                            const std::function<bool()>& beside_done,
                            const std::function<bool()>& stop);

}  // namespace dampbound::detail
