#include "app/wait_note.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstdlib>

namespace dampbound::app {

namespace {

std::atomic<bool> g_interrupted{false};
std::atomic<double> g_first{2.0}, g_every{5.0};

extern "C" void wait_note_interrupt(int) { g_interrupted.store(true); }

}  // namespace

void WaitNote::set_delays(double first_s, double every_s) {
  g_first.store(first_s);
  g_every.store(every_s);
}

WaitNote::WaitNote(std::string command, std::string left)
    : command_(std::move(command)), left_(std::move(left)) {
  start_ = std::chrono::steady_clock::now();
  // DAMPBOUND_PROGRESS_AFTER: the first delay in seconds (tests make it short).
  if (const char* after = std::getenv("DAMPBOUND_PROGRESS_AFTER")) {
    const double s = std::atof(after);
    if (s >= 0) set_delays(s, std::max(s, 0.2));
  }
  previous_interrupt_ = std::signal(SIGINT, wait_note_interrupt);
  if (previous_interrupt_ == SIG_ERR) previous_interrupt_ = SIG_DFL;
  thread_ = std::thread([this] { loop(); });
}

WaitNote::~WaitNote() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
  std::signal(SIGINT, previous_interrupt_);
  if (said_) {
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    std::fprintf(stderr, "%sdampbound: %s: done in %.0f s\n", isatty(2) ? "\r\033[K" : "",
                 command_.c_str(), s);
  }
}

void WaitNote::stage(const std::string& what, int done, int total) {
  std::lock_guard<std::mutex> lock(mutex_);
  what_ = what;
  done_ = done;
  total_ = total;
}

std::string WaitNote::line_locked(double seconds) const {
  char counts[64] = "";
  if (total_ > 0) std::snprintf(counts, sizeof counts, " (%d of %d done)", done_, total_);
  char time[64];
  std::snprintf(time, sizeof time, ": %.0f s", seconds);
  return "dampbound: " + command_ + ": " + what_ + counts + time +
         " (Ctrl-C stops)";
}

void WaitNote::loop() {
  const bool tty = isatty(2);
  std::unique_lock<std::mutex> lock(mutex_);
  auto last_said = std::chrono::steady_clock::time_point{};
  while (!stop_) {
    wake_.wait_for(lock, std::chrono::milliseconds(100));
    if (stop_) break;
    const auto now = std::chrono::steady_clock::now();
    if (g_interrupted.load()) {
      std::fprintf(stderr, "%sdampbound: %s: interrupted during %s; %s\n",
                   tty ? "\r\033[K" : "", command_.c_str(), what_.c_str(), left_.c_str());
      std::fflush(stdout);
      std::_Exit(130);
    }
    const double waited = std::chrono::duration<double>(now - start_).count();
    if (waited < g_first.load()) continue;
    const double since = std::chrono::duration<double>(now - last_said).count();
    if (said_ && since < (tty ? 1.0 : g_every.load())) continue;
    const std::string text = line_locked(waited);
    std::fprintf(stderr, tty ? "\r\033[K%s" : "%s\n", text.c_str());
    std::fflush(stderr);
    said_ = true;
    last_said = now;
  }
}

}  // namespace dampbound::app
