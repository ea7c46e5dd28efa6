#pragma once
// Progress on every wait over 2 s: while a WaitNote lives and 2 s have passed, the stage that
// runs is said on stderr with its name, its counts and the seconds so far (rewritten in place on
// a terminal, a new line every 5 s otherwise), so that no command sits silent. Ctrl-C while
// one lives ends the command at once with one line saying what it interrupted, exit 130:
// the commands that use it write no file before they finish, so nothing is left half done.
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace dampbound::app {

class WaitNote {
 public:
  /// `command`: the subcommand's name, the prefix of every line ("dampbound: bounds: ...");
  /// `left`: what an interrupt leaves behind, said in its line.
  explicit WaitNote(std::string command, std::string left = "nothing was written");
  ~WaitNote();
  WaitNote(const WaitNote&) = delete;
  WaitNote& operator=(const WaitNote&) = delete;

  /// A new stage: its words, and "done of total" when total > 0.
  void stage(const std::string& what, int done = 0, int total = 0);

  /// The delay before the first line and between lines on a pipe (tests shorten it).
  static void set_delays(double first_s, double every_s);

 private:
  void loop();
  std::string line_locked(double seconds) const;

  std::string command_, left_, what_;
  int done_ = 0, total_ = 0;
  std::chrono::steady_clock::time_point start_;
  bool said_ = false, stop_ = false;
  void (*previous_interrupt_)(int) = nullptr;  ///< restored when the note ends
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::thread thread_;
};

}  // namespace dampbound::app
