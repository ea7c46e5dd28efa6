#include "ui/close_guard.hpp"

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <ctime>

namespace dampbound::ui {

namespace {
std::atomic<int> g_signal{0};

sigset_t close_signals() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  return set;
}

std::chrono::steady_clock::duration seconds(double s) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(s));
}
}  // namespace

void block_close_signals() {
  const sigset_t set = close_signals();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
}

CloseGuard::CloseGuard(double grace_s, double hang_s)
    : grace_s_(grace_s), hang_s_(hang_s), beat_at_(Clock::now()), thread_([this] { watch(); }) {}

CloseGuard::~CloseGuard() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void CloseGuard::catch_signals() {
  block_close_signals();  // in case the caller has not (its later threads then inherit it)
  signals_ = true;
}

void CloseGuard::on_signal(std::function<void()> fn) {
  std::lock_guard<std::mutex> lock(mutex_);  // the watchdog reads it under the lock
  on_signal_ = std::move(fn);
  if (on_signal_ && g_signal.load() != 0) on_signal_();
}

bool CloseGuard::signalled() {
  return g_signal.load() != 0;
}

void CloseGuard::request_close() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (closing_) return;
  closing_ = true;
  close_at_ = Clock::now();
}

void CloseGuard::heartbeat(const std::string& doing) {
  std::lock_guard<std::mutex> lock(mutex_);
  beat_at_ = Clock::now();
  doing_ = doing;
}

void CloseGuard::watch() {
  // This thread takes the close signals itself, so it needs them blocked like every other.
  block_close_signals();
  const sigset_t set = close_signals();
  const timespec poll = {0, 5 * 1000 * 1000};  // 5 ms
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_) {
    if (signals_) {
      lock.unlock();
      const int sig = sigtimedwait(&set, nullptr, &poll);
      lock.lock();
      if (sig > 0) {
        g_signal.store(sig);
        if (on_signal_) on_signal_();
        if (!closing_) {
          closing_ = true;
          close_at_ = Clock::now();
        }
      }
    } else {
      wake_.wait_for(lock, std::chrono::milliseconds(5));
    }
    if (stop_) break;
    const Clock::time_point now = Clock::now();
    if (closing_ && now - close_at_ > seconds(grace_s_)) {
      std::fprintf(stderr, "dampbound: closing without waiting for the background work\n");
      std::fflush(nullptr);
      std::_Exit(0);
    }
    if (hang_s_ > 0 && now - beat_at_ > seconds(hang_s_)) {
      std::fprintf(stderr, "dampbound: a frame took over %g s (%s): hung\n", hang_s_,
                   doing_.c_str());
      std::fflush(nullptr);
      std::_Exit(3);
    }
  }
}

}  // namespace dampbound::ui
