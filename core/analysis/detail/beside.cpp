// clang-format off
#include "core/physics/detail/gcc_warnings.hpp"  // first: silences GCC 12 false positives
// clang-format on
#include "core/analysis/detail/beside.hpp"

#include <algorithm>
#include <utility>

namespace dampbound::detail {

int resolved_threads(int threads) {
  return threads > 0 ? threads
                     : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

Beside::Beside(std::function<void()> work)
    : thread_([this, work = std::move(work)] {
        try {
          work();
        } catch (...) {
          error_ = std::current_exception();
        }
        done_.store(true, std::memory_order_release);
      }) {}

Beside::~Beside() {
  if (thread_.joinable()) thread_.join();
}

void Beside::finish() {
  thread_.join();
  if (error_) std::rethrow_exception(error_);
}

TopEstimate estimate_beside(const SparseMatrix& S, int cores,
                            const std::function<bool()>& beside_done,
                            const std::function<bool()>& stop) {
  LanczosRecurrence<float> lanczos(S, cores - 1);
  bool all_threads = false;
  return lanczos_estimate(lanczos, S.rows(), kLanczosSteps, kLanczosCheck, 1e-7, [&] {
    if (stop()) return false;
    if (!all_threads && beside_done()) {
      all_threads = true;
      lanczos.set_threads(cores);
    }
    return true;
  });
}

}  // namespace dampbound::detail
