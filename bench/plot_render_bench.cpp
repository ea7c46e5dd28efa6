// Frame time of the plot widget rendered headless through the EGL host (Mesa llvmpipe on CI):
// a 1200 x 700 line plot, and the damping-bounds plot with two 10000-point traces over a
// band (the plots tests/ui/egl_render_test.cpp checks pixel by pixel). Each iteration draws
// one frame and reads it back; the counters give the host's own split (milliseconds).
#include <benchmark/benchmark.h>

#if defined(DAMPBOUND_HAVE_EGL)
#include <memory>

#include "tests/ui/plot_specs.hpp"
#include "ui/egl_host.hpp"
#include "ui/figure.hpp"

namespace {

using namespace dampbound::ui;

EglHost& host() {
  static std::unique_ptr<EglHost> h = std::make_unique<EglHost>();
  return *h;
}

void render(benchmark::State& state, const PlotSpec& spec) {
  const FrameFn frame = plot_frame(spec);
  host().render_frames(1200, 700, frame, 1);  // fonts and shaders made before timing
  for (auto _ : state) benchmark::DoNotOptimize(host().render_frames(1200, 700, frame, 1));
  const RenderStats& st = host().last_stats();
  state.counters["frame_ms"] = st.mean_frame_ms;
  state.counters["readback_ms"] = st.readback_ms;
}

void BM_LinePlot(benchmark::State& state) {
  render(state, line_spec());
}
BENCHMARK(BM_LinePlot)->Unit(benchmark::kMillisecond);

void BM_BandAndTwoTraces(benchmark::State& state) {
  render(state, band_spec());
}
BENCHMARK(BM_BandAndTwoTraces)->Unit(benchmark::kMillisecond);

}  // namespace
#endif  // DAMPBOUND_HAVE_EGL

BENCHMARK_MAIN();
