#pragma once
// The tuner's background work (the exact analysis, Suggest, the Map) runs at a lower priority
// than the frames: on a machine whose cores the playing mesh and the rasteriser already fill,
// a worker at the same priority takes its share of every frame (the first two seconds of a
// 40k-node plane played at 120 to 140 ms per frame while its analysis ran, 70 ms after).
// Threads the worker starts (the Lanczos products' pool) inherit the priority.

namespace dampbound::ui {

/// The nice value of a worker thread: a weight of about a tenth of the frames' (Linux's
/// scheduler gives nice 10 a weight of 110 against 1024 at nice 0).
constexpr int kWorkerNice = 10;

/// Lowers the calling thread's priority to kWorkerNice (Linux: nice is per thread). Returns
/// false where the system does not allow it; the work then runs at the frames' priority.
bool lower_worker_priority();

/// The calling thread's nice value (tests).
int worker_nice();

}  // namespace dampbound::ui
