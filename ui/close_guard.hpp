#pragma once
// Closing the tuner is immediate: once a close is requested (the window's close button,
// SIGTERM, SIGINT), the process ends within a grace period whatever its threads are doing; the
// frame loop saves the settings and exits without waiting for background work (a worker in
// the middle of a factorisation cannot be interrupted). For `gui --self-test` it also ends the
// process, with a message, when one frame takes longer than a limit: a hang fails the test
// instead of stalling it.
//
// SIGINT and SIGTERM are blocked in every thread (block_close_signals(), before the first
// thread starts: threads inherit the mask) and taken by the watchdog thread with sigtimedwait,
// so no signal handler runs: LLVM (llvmpipe's shader compiler) installs handlers of its own
// for SIGTERM and SIGINT when it compiles, and a SIGTERM delivered through them to the
// frame's thread crashed the tuner in longjmp (exit 139, 2 of about 25 closes on tissue-block).
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

namespace dampbound::ui {

/// Blocks SIGINT and SIGTERM in the calling thread and in every thread it starts afterwards.
/// Call first thing, before any thread (GLFW, Mesa, the node pool, workers) exists.
void block_close_signals();

class CloseGuard {
 public:
  /// grace_s: the most a close may take; hang_s > 0: the most one frame may take.
  explicit CloseGuard(double grace_s, double hang_s = 0.0);
  ~CloseGuard();
  CloseGuard(const CloseGuard&) = delete;
  CloseGuard& operator=(const CloseGuard&) = delete;

  /// The watchdog takes SIGINT and SIGTERM (blocked by block_close_signals()): each requests
  /// the close. The destructor leaves them blocked and pending.
  void catch_signals();
  /// Called on the watchdog thread when a signal requests the close (before the frame loop
  /// sees it): the tuner stops stepping there, so the frame under way ends sooner. Called
  /// at once when a signal came before it was set.
  void on_signal(std::function<void()> fn);
  /// True once SIGINT or SIGTERM arrived.
  static bool signalled();
  /// Starts the grace period (idempotent; any thread).
  void request_close();
  /// A frame ended; `doing` says what comes next (named in a hang's message).
  void heartbeat(const std::string& doing = std::string());

 private:
  void watch();

  using Clock = std::chrono::steady_clock;
  const double grace_s_, hang_s_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false, closing_ = false;
  std::atomic<bool> signals_{false};
  Clock::time_point close_at_, beat_at_;
  std::string doing_;
  std::function<void()> on_signal_;
  std::thread thread_;  // last: it starts once the members above exist
};

}  // namespace dampbound::ui
