#include "ui/tuner_trace.hpp"

#include <algorithm>
#include <cmath>

namespace dampbound::ui {

namespace {
/// min/max that ignore NaN on either side (std::fmin/fmax semantics).
double lo_of(double a, double b) {
  return std::fmin(a, b);
}
double hi_of(double a, double b) {
  return std::fmax(a, b);
}
}  // namespace

void merge_min(StepStats& lo, const StepStats& s) {
  lo.iteration = std::min(lo.iteration, s.iteration);
  lo.time = lo_of(lo.time, s.time);
  lo.watched_displacement = lo_of(lo.watched_displacement, s.watched_displacement);
  lo.watched_lower = lo_of(lo.watched_lower, s.watched_lower);
  lo.watched_upper = lo_of(lo.watched_upper, s.watched_upper);
  lo.watched_gamma = lo_of(lo.watched_gamma, s.watched_gamma);
  lo.watched_gamma_eff = lo_of(lo.watched_gamma_eff, s.watched_gamma_eff);
  lo.max_displacement = lo_of(lo.max_displacement, s.max_displacement);
  lo.violating = std::min(lo.violating, s.violating);
  lo.unstabilisable = std::min(lo.unstabilisable, s.unstabilisable);
  lo.clamped = std::min(lo.clamped, s.clamped);
  lo.zero_length_springs = std::min(lo.zero_length_springs, s.zero_length_springs);
  lo.finite = lo.finite && s.finite;
}

void merge_max(StepStats& hi, const StepStats& s) {
  hi.iteration = std::max(hi.iteration, s.iteration);
  hi.time = hi_of(hi.time, s.time);
  hi.watched_displacement = hi_of(hi.watched_displacement, s.watched_displacement);
  hi.watched_lower = hi_of(hi.watched_lower, s.watched_lower);
  hi.watched_upper = hi_of(hi.watched_upper, s.watched_upper);
  hi.watched_gamma = hi_of(hi.watched_gamma, s.watched_gamma);
  hi.watched_gamma_eff = hi_of(hi.watched_gamma_eff, s.watched_gamma_eff);
  hi.max_displacement = hi_of(hi.max_displacement, s.max_displacement);
  hi.violating = std::max(hi.violating, s.violating);
  hi.unstabilisable = std::max(hi.unstabilisable, s.unstabilisable);
  hi.clamped = std::max(hi.clamped, s.clamped);
  hi.zero_length_springs = std::max(hi.zero_length_springs, s.zero_length_springs);
  hi.finite = hi.finite && s.finite;
}

TraceDecimator::TraceDecimator(size_t max_buckets)
    : max_buckets_(std::max<size_t>(max_buckets, 2)) {}

void TraceDecimator::add(const StepStats& s) {
  if (partial_.count == 0) {
    partial_.lo = partial_.hi = s;
  } else {
    merge_min(partial_.lo, s);
    merge_max(partial_.hi, s);
  }
  if (++partial_.count < bucket_) return;
  full_.push_back(partial_);
  partial_ = Bucket{};
  if (full_.size() < max_buckets_) return;
  // Too many buckets: merge neighbours, doubling the bucket size.
  std::vector<Bucket> merged;
  merged.reserve(full_.size() / 2 + 1);
  for (size_t i = 0; i + 1 < full_.size(); i += 2) {
    Bucket b = full_[i];
    merge_min(b.lo, full_[i + 1].lo);
    merge_max(b.hi, full_[i + 1].hi);
    b.count += full_[i + 1].count;
    merged.push_back(b);
  }
  if (full_.size() % 2 == 1) partial_ = full_.back();  // an odd one out becomes partial
  full_ = std::move(merged);
  bucket_ *= 2;
}

void TraceDecimator::rebuild_output() {
  out_.clear();
  auto emit = [&](const Bucket& b) {
    if (b.count == 1) {
      out_.push_back(b.lo);
    } else {
      out_.push_back(b.lo);
      out_.push_back(b.hi);
    }
  };
  for (const Bucket& b : full_) emit(b);
  if (partial_.count > 0) emit(partial_);
}

const std::vector<StepStats>& TraceDecimator::update(const std::vector<StepStats>& trace,
                                                     std::uint64_t generation) {
  if (generation != generation_ || trace.size() < consumed_) {
    generation_ = generation;
    bucket_ = 1;
    consumed_ = 0;
    full_.clear();
    partial_ = Bucket{};
    out_.clear();
  }
  if (trace.size() == consumed_) return out_;
  for (size_t i = consumed_; i < trace.size(); ++i) add(trace[i]);
  consumed_ = trace.size();
  rebuild_output();
  return out_;
}

}  // namespace dampbound::ui
