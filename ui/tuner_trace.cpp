#include "ui/tuner_trace.hpp"

#include <algorithm>
#include <cmath>

namespace dampbound::ui {

void merge_into(StepSample& e, const StepSample& s, BucketEnd which) {
  const bool lo = which == BucketEnd::lo;
  // std::fmin / std::fmax ignore a NaN on either side.
  const auto real = [lo](double& a, double b) { a = lo ? std::fmin(a, b) : std::fmax(a, b); };
  const auto count = [lo](int& a, int b) { a = lo ? std::min(a, b) : std::max(a, b); };
  count(e.iteration, s.iteration);
  real(e.time, s.time);
  real(e.watched.displacement, s.watched.displacement);
  real(e.watched.lower, s.watched.lower);
  real(e.watched.upper, s.watched.upper);
  real(e.watched.gamma, s.watched.gamma);
  real(e.watched.gamma_eff, s.watched.gamma_eff);
  real(e.max_displacement, s.max_displacement);
  count(e.violating, s.violating);
  count(e.unstabilisable, s.unstabilisable);
  count(e.clamped, s.clamped);
  count(e.zero_length_springs, s.zero_length_springs);
  e.finite = e.finite && s.finite;
  real(e.watched.safe, s.watched.safe);
  count(e.unguaranteed, s.unguaranteed);
  count(e.compressed_springs, s.compressed_springs);
}

TraceDecimator::TraceDecimator(size_t max_buckets)
    : max_buckets_(std::max<size_t>(max_buckets, 2)) {}

void TraceDecimator::add(const StepSample& s) {
  if (partial_.count == 0) {
    partial_.lo = partial_.hi = s;
  } else {
    merge_into(partial_.lo, s, BucketEnd::lo);
    merge_into(partial_.hi, s, BucketEnd::hi);
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
    merge_into(b.lo, full_[i + 1].lo, BucketEnd::lo);
    merge_into(b.hi, full_[i + 1].hi, BucketEnd::hi);
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

const std::vector<StepSample>& TraceDecimator::update(const std::vector<StepSample>& trace,
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
