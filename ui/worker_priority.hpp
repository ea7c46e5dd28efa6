#pragma once
// The tuner's background work (the exact analysis, Suggest, the Map) runs at a lower priority
// than the frames: on a machine whose cores the playing mesh and the rasteriser already fill,
// a worker at the same priority takes its share of every frame (with the exact analysis
// following the state of a playing 40k-node plane: mean frame 72 to 73 ms at the frames'
// priority, 64 to 70 ms at nice 10; at the static equilibrium of a loaded one 59 to 61 ms at
// nice 10, 51 to 55 ms at nice 19; docs/performance.md).
// Threads the worker starts (the Lanczos products' pool) inherit the priority.

namespace dampbound::ui {

/// The nice value of a worker thread, the lowest: Linux's scheduler gives nice 19 a weight of
/// 15 against 1024 at nice 0, so a worker runs mostly where the frames leave a core idle.
constexpr int kWorkerNice = 19;

/// Lowers the calling thread's priority to kWorkerNice (Linux: nice is per thread). Returns
/// false where the system does not allow it; the work then runs at the frames' priority.
bool lower_worker_priority();

/// The calling thread's nice value (tests).
int worker_nice();

}  // namespace dampbound::ui
