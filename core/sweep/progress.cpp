#include "core/io/format.hpp"
#include "core/sweep/progress.hpp"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <string>

namespace dampbound {

std::string format_duration(double s) {
  if (!std::isfinite(s) || s < 0) return "?";
  const long t = std::lround(s);
  char buf[32];
  if (t >= 3600)
    c_snprintf(buf, sizeof buf, "%ldh%02ldm", t / 3600, (t / 60) % 60);
  else if (t >= 60)
    c_snprintf(buf, sizeof buf, "%ldm%02lds", t / 60, t % 60);
  else
    c_snprintf(buf, sizeof buf, "%lds", t);
  return buf;
}

ProgressPrinter::ProgressPrinter(std::FILE* out, bool terminal, double interval_s)
    : out_(out), terminal_(terminal), interval_s_(interval_s) {}

void ProgressPrinter::update(const SweepProgress& p) {
  const CNumericScope c;  // "12.5%", whatever the host's locale
  constexpr double kWindow = 300;
  if (window_.empty() || p.elapsed_s - window_.back().t >= 1.0)
    window_.push_back({p.elapsed_s, p.classes_done, p.trials_done});
  while (window_.size() > 2 && p.elapsed_s - window_[1].t >= kWindow) window_.pop_front();
  // Trials per second counts the trials covered by the classes finished (in this run).
  double trial_rate = NAN, class_rate = NAN;
  if (p.final) {
    const double run_s = std::max(p.elapsed_s, 1e-9);
    trial_rate = static_cast<double>(p.trials_done - p.trials_resumed) / run_s;
  } else if (p.elapsed_s - window_.front().t > 0.5) {
    const Sample& a = window_.front();
    const double dt = p.elapsed_s - a.t;
    trial_rate = static_cast<double>(p.trials_done - a.trials) / dt;
    class_rate = static_cast<double>(p.classes_done - a.classes) / dt;
  }
  const double left =
      class_rate > 0 ? static_cast<double>(p.classes_total - p.classes_done) / class_rate : NAN;
  const double frac = p.trials_total
                          ? static_cast<double>(p.trials_done) / static_cast<double>(p.trials_total)
                          : 1.0;
  char rate[32];
  if (!std::isfinite(trial_rate))
    c_snprintf(rate, sizeof rate, "?");
  else if (trial_rate >= 1e4)
    c_snprintf(rate, sizeof rate, "%.1fk", trial_rate / 1e3);
  else
    c_snprintf(rate, sizeof rate, "%.0f", trial_rate);
  if (terminal_) {
    if (!p.final && p.elapsed_s - last_draw_ < 0.2) return;
    last_draw_ = p.elapsed_s;
    const int width = 30;
    const int filled = static_cast<int>(frac * width);
    std::string bar(static_cast<size_t>(filled), '#');
    bar.resize(width, '.');
    std::fprintf(out_, "\r[%s] %5.1f%%  %" PRIu64 "/%" PRIu64 " trials  %s trials/s  %s %s   ",
                 bar.c_str(), 100 * frac, p.trials_done, p.trials_total, rate,
                 p.final ? "took" : "left", format_duration(p.final ? p.elapsed_s : left).c_str());
    if (p.final) std::fputc('\n', out_);
    std::fflush(out_);
    return;
  }
  if (!p.final && p.elapsed_s - last_print_ < interval_s_) return;
  last_print_ = p.elapsed_s;
  std::fprintf(out_,
               "sweep: %.1f%% %" PRIu64 "/%" PRIu64 " trials, %" PRIu64 "/%" PRIu64
               " classes, %s trials/s, %s %s\n",
               100 * frac, p.trials_done, p.trials_total, p.classes_done, p.classes_total, rate,
               format_duration(p.final ? p.elapsed_s : left).c_str(), p.final ? "elapsed" : "left");
  std::fflush(out_);
}

}  // namespace dampbound
