#pragma once
// A growing trace reduced for plotting: min/max per bucket of iterations, updated
// incrementally, so a run of a million steps costs the plots what a few thousand do.
// No GL (tests/ui/tuner_trace_test.cpp).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "dampbound/physics/step.hpp"

namespace dampbound::ui {

/// Keeps at most about 2 * max_buckets samples of a trace that only grows (until it starts
/// over). While the trace is short every sample is kept as is; beyond max_buckets samples,
/// consecutive samples are grouped into buckets whose size doubles as needed, and each bucket
/// contributes two samples: the field-wise minima at its first iteration and the field-wise
/// maxima at its last (what a min/max per-pixel-column plot would draw anyway). NaN fields
/// are ignored by the minima and maxima.
class TraceDecimator {
 public:
  explicit TraceDecimator(size_t max_buckets = 2048);

  /// Brings the reduced trace up to date with `trace`: reads only the samples added since the
  /// last call, and starts over when `generation` changed or the trace got shorter.
  const std::vector<StepSample>& update(const std::vector<StepSample>& trace,
                                       std::uint64_t generation = 0);
  /// The reduced trace of the last update().
  const std::vector<StepSample>& reduced() const { return out_; }
  /// Samples per bucket now (1 while every sample is kept).
  size_t bucket_size() const { return bucket_; }

 private:
  struct Bucket {
    StepSample lo, hi;
    size_t count = 0;
  };
  void add(const StepSample& s);
  void rebuild_output();

  size_t max_buckets_;
  size_t bucket_ = 1;
  size_t consumed_ = 0;
  std::uint64_t generation_ = 0;
  std::vector<Bucket> full_;
  Bucket partial_;
  std::vector<StepSample> out_;
};

/// The end of a bucket a merge builds: its field-wise minima or maxima.
enum class BucketEnd { lo, hi };

/// Field-wise merge of `s` into a bucket end: `lo` keeps minima (and the earlier iteration),
/// `hi` maxima (and the later one); a NaN field is ignored, `finite` holds only when both are
/// finite. One fold over every field of StepSample serves both ends. Exposed for tests.
void merge_into(StepSample& end, const StepSample& s, BucketEnd which);

}  // namespace dampbound::ui
