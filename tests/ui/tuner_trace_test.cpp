// The plot decimation of a growing trace (ui/tuner_trace.hpp): bounded size, extremes kept,
// incremental equals one-shot, restarts.
#include "ui/tuner_trace.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace dampbound::ui {
namespace {

std::vector<StepSample> make_trace(int n) {
  std::vector<StepSample> t(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    StepSample& s = t[static_cast<size_t>(i)];
    s.iteration = i + 1;
    s.time = 0.05 * (i + 1);
    s.watched.displacement = 5.0 * std::exp(-i / 3000.0) * std::abs(std::cos(i * 0.37));
    s.max_displacement = s.watched.displacement + 0.1;
    s.watched.lower = 0.002;
    s.watched.upper = i % 97 == 0 ? std::numeric_limits<double>::infinity() : 0.01 + i * 1e-6;
    s.violating = i % 13;
  }
  return t;
}

double max_of(const std::vector<StepSample>& t) {
  double m = 0;
  for (const auto& s : t) m = std::max(m, s.watched.displacement);
  return m;
}

TEST(TraceDecimator, ShortTracesAreKeptExactly) {
  TraceDecimator d(64);
  const auto t = make_trace(50);
  const auto& r = d.update(t);
  ASSERT_EQ(r.size(), 50u);
  for (size_t i = 0; i < r.size(); ++i) {
    EXPECT_EQ(r[i].iteration, t[i].iteration);
    EXPECT_EQ(r[i].watched.displacement, t[i].watched.displacement);
  }
  EXPECT_EQ(d.bucket_size(), 1u);
}

TEST(TraceDecimator, LongTracesStayBoundedAndKeepTheExtremes) {
  TraceDecimator d(256);
  const auto t = make_trace(100000);
  const auto& r = d.update(t);
  EXPECT_LE(r.size(), 2u * 256u + 2u);
  EXPECT_GE(r.size(), 256u);
  EXPECT_EQ(r.front().iteration, 1);
  EXPECT_EQ(r.back().iteration, 100000);
  EXPECT_DOUBLE_EQ(max_of(r), max_of(t));
  // Iterations never go backwards, and the infinite upper bound survives as a maximum.
  for (size_t i = 1; i < r.size(); ++i) EXPECT_LE(r[i - 1].iteration, r[i].iteration);
  EXPECT_TRUE(std::any_of(r.begin(), r.end(),
                          [](const StepSample& s) { return std::isinf(s.watched.upper); }));
  EXPECT_TRUE(
      std::any_of(r.begin(), r.end(), [](const StepSample& s) { return s.violating == 12; }));
}

TEST(TraceDecimator, IncrementalUpdatesEqualOneShot) {
  const auto t = make_trace(20000);
  TraceDecimator once(128), step(128);
  const auto& a = once.update(t);
  std::vector<StepSample> growing;
  for (size_t i = 0; i < t.size(); i += 777) {
    growing.insert(growing.end(), t.begin() + static_cast<long>(i),
                   t.begin() + static_cast<long>(std::min(i + 777, t.size())));
    step.update(growing);
  }
  const auto& b = step.reduced();
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].iteration, b[i].iteration);
    EXPECT_EQ(a[i].watched.displacement, b[i].watched.displacement);
  }
}

TEST(TraceDecimator, StartsOverOnANewGenerationOrAShorterTrace) {
  TraceDecimator d(64);
  d.update(make_trace(1000), 1);
  EXPECT_EQ(d.update(make_trace(10), 1).size(), 10u);  // shorter: starts over
  EXPECT_EQ(d.update(make_trace(10), 2).size(), 10u);
  EXPECT_TRUE(d.update({}, 3).empty());
}

TEST(TraceDecimator, MergeIgnoresNaN) {
  StepSample lo, hi, s;
  lo.watched.displacement = 1;
  hi.watched.displacement = 1;
  s.watched.displacement = std::numeric_limits<double>::quiet_NaN();
  merge_into(lo, s, BucketEnd::lo);
  merge_into(hi, s, BucketEnd::hi);
  EXPECT_EQ(lo.watched.displacement, 1);
  EXPECT_EQ(hi.watched.displacement, 1);
  s.finite = false;
  merge_into(hi, s, BucketEnd::hi);
  EXPECT_FALSE(hi.finite);
}

TEST(TraceDecimator, MergeFoldsEveryField) {
  // Each end takes the minima or the maxima of every field, the SPEC 9 ones included.
  StepSample a, b;
  a.iteration = 3, b.iteration = 7;
  a.time = 0.3, b.time = 0.7;
  a.watched.safe = 2, b.watched.safe = 5;
  a.unguaranteed = 4, b.unguaranteed = 1;
  a.compressed_springs = 0, b.compressed_springs = 9;
  a.violating = 2, b.violating = 6;
  StepSample lo = a, hi = a;
  merge_into(lo, b, BucketEnd::lo);
  merge_into(hi, b, BucketEnd::hi);
  EXPECT_EQ(lo.iteration, 3);
  EXPECT_EQ(hi.iteration, 7);
  EXPECT_EQ(lo.time, 0.3);
  EXPECT_EQ(hi.time, 0.7);
  EXPECT_EQ(lo.watched.safe, 2);
  EXPECT_EQ(hi.watched.safe, 5);
  EXPECT_EQ(lo.unguaranteed, 1);
  EXPECT_EQ(hi.unguaranteed, 4);
  EXPECT_EQ(lo.compressed_springs, 0);
  EXPECT_EQ(hi.compressed_springs, 9);
  EXPECT_EQ(lo.violating, 2);
  EXPECT_EQ(hi.violating, 6);
}

}  // namespace
}  // namespace dampbound::ui
