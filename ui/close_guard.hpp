#pragma once
// Closing the tuner is immediate: once a close is requested (the window's close button,
// SIGTERM, SIGINT), the process ends within a grace period whatever its threads are doing; the
// frame loop saves the settings and exits without waiting for background work (a worker in
// the middle of a factorisation cannot be interrupted). For `gui --self-test` it also ends the
// process, with a message, when one frame takes longer than a limit: a hang fails the test
// instead of stalling it.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace dampbound::ui {

class CloseGuard {
 public:
  /// grace_s: the most a close may take; hang_s > 0: the most one frame may take.
  explicit CloseGuard(double grace_s, double hang_s = 0.0);
  ~CloseGuard();
  CloseGuard(const CloseGuard&) = delete;
  CloseGuard& operator=(const CloseGuard&) = delete;

  /// Installs SIGINT and SIGTERM handlers that request the close (and restores the defaults
  /// on destruction).
  void catch_signals();
  /// True once SIGINT or SIGTERM arrived.
  static bool signalled();
  /// Starts the grace period (idempotent).
  void request_close();
  /// A frame ended; `doing` says what comes next (named in a hang's message).
  void heartbeat(const std::string& doing = std::string());

 private:
  void watch();

  using Clock = std::chrono::steady_clock;
  const double grace_s_, hang_s_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false, closing_ = false, signals_ = false;
  Clock::time_point close_at_, beat_at_;
  std::string doing_;
  std::thread thread_;  // last: it starts once the members above exist
};

}  // namespace dampbound::ui
