#include "ui/close_guard.hpp"

#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>

namespace dampbound::ui {

namespace {
std::atomic<int> g_signal{0};
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs a lock-free flag");

extern "C" void on_close_signal(int sig) {
  g_signal.store(sig);
}

std::chrono::steady_clock::duration seconds(double s) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(s));
}
}  // namespace

CloseGuard::CloseGuard(double grace_s, double hang_s)
    : grace_s_(grace_s), hang_s_(hang_s), beat_at_(Clock::now()), thread_([this] { watch(); }) {}

CloseGuard::~CloseGuard() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
  if (signals_) {
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
  }
}

void CloseGuard::catch_signals() {
  signals_ = true;
  std::signal(SIGINT, on_close_signal);
  std::signal(SIGTERM, on_close_signal);
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
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_) {
    // The signal handler only sets a flag: it is seen here within a poll period.
    wake_.wait_for(lock, std::chrono::milliseconds(10));
    if (stop_) break;
    const Clock::time_point now = Clock::now();
    if (!closing_ && g_signal.load() != 0) {
      closing_ = true;
      close_at_ = now;
    }
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
