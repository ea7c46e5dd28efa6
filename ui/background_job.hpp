#pragma once
// One computation on a worker thread while the window keeps drawing: the frame polls for its
// result, reads where it is, and may cancel it. Suggest and the substeps of the Suggest tab
// share this (the exact analysis, trial runs and verifying runs take seconds to minutes).
#include <atomic>
#include <chrono>
#include <exception>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace dampbound::ui {

/// What a running job shares with the frame: its progress line and the cancel request.
class JobControl {
 public:
  /// Says where the job is (the frame shows it); false when the job should stop now.
  bool report(std::string text) {
    const std::lock_guard<std::mutex> lock(mutex_);
    text_ = std::move(text);
    return !cancel_;
  }
  bool cancelled() const { return cancel_; }
  void cancel() { cancel_ = true; }
  std::string text() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return text_;
  }

 private:
  std::atomic<bool> cancel_{false};
  mutable std::mutex mutex_;
  std::string text_;
};

/// A computation of a T on a worker thread, at most one at a time.
template <class T>
class BackgroundJob {
 public:
  BackgroundJob() = default;
  BackgroundJob(const BackgroundJob&) = delete;
  BackgroundJob& operator=(const BackgroundJob&) = delete;
  ~BackgroundJob() {
    wait();
    for (auto& f : dropped_) f.wait();
  }

  /// Runs fn(JobControl&) -> T on a worker thread; ignored while one runs. fn stops early by
  /// throwing when JobControl::report() returns false (its result is dropped anyway).
  template <class Fn>
  void launch(Fn fn) {
    if (busy()) return;
    error_.clear();
    cancelled_ = false;
    started_ = std::chrono::steady_clock::now();
    control_ = std::make_shared<JobControl>();
    pending_ = std::async(std::launch::async,
                          [fn = std::move(fn), control = control_]() mutable { return fn(*control); });
  }
  /// True while a computation runs.
  bool busy() const { return pending_.valid(); }
  /// Collects a finished computation (call once per frame); true when a result arrived.
  bool poll() {
    // Cancelled computations that have ended are joined here, never by a frame waiting.
    for (size_t i = dropped_.size(); i-- > 0;)
      if (dropped_[i].wait_for(std::chrono::seconds(0)) == std::future_status::ready)
        dropped_.erase(dropped_.begin() + static_cast<std::ptrdiff_t>(i));
    if (!busy()) return false;
    if (pending_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return false;
    try {
      result_ = pending_.get();
    } catch (const std::exception& e) {
      error_ = e.what();
      result_.reset();
    }
    return true;
  }
  /// Waits for a running computation (tests, scripted runs).
  void wait() {
    if (busy()) pending_.wait();
    poll();
  }
  /// The Cancel button: the running computation's result is dropped and its worker stops at
  /// its next report(); it is joined later, and closing the window does not wait for it.
  void cancel() {
    if (!busy()) return;
    control_->cancel();
    dropped_.push_back(std::move(pending_));
    cancelled_ = true;
  }
  /// Another scene: the running computation is cancelled and the last result and error
  /// dropped, so that nothing of the old scene stays on show (or applies).
  void clear() {
    cancel();
    cancelled_ = false;
    result_.reset();
    error_.clear();
  }
  /// Seconds since the running computation started.
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
  }
  /// The running computation's last report() (empty before its first).
  std::string progress() const { return control_ ? control_->text() : std::string(); }
  /// True when the last computation was cancelled (nothing new to show).
  bool cancelled() const { return cancelled_; }
  /// The last finished result.
  const std::optional<T>& result() const { return result_; }
  /// One line when the computation threw.
  const std::string& error() const { return error_; }

 private:
  std::future<T> pending_;
  std::shared_ptr<JobControl> control_;
  std::vector<std::future<T>> dropped_;  ///< cancelled, not yet joined
  std::chrono::steady_clock::time_point started_{};
  bool cancelled_ = false;
  std::optional<T> result_;
  std::string error_;
};

}  // namespace dampbound::ui
