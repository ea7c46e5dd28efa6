#pragma once
// CHOLMOD's OpenMP loops, run on the calling thread alone while it factors or solves.
//
// Debian's libcholmod (SuiteSparse 5.12) is built with OpenMP and asks for
// CHOLMOD_OMP_NUM_THREADS = 4 threads in its loops (scattering A into a supernode, clearing
// blocks), whatever the machine. Those loops are small; on 2 cores each factorisation of the
// 200 x 200 plane's matrix spent about two thirds of its time waking and parking threads
// (0.5 to 0.8 s against 0.16 to 0.26 s serial, 100 000 context switches per run of
// bench/exact_limits_bench; docs/performance.md). The numeric work is in the BLAS, which this
// does not touch.
//
// The guard sets OpenMP's max-active-levels to 0 for the calling thread (in libgomp since
// GCC 11 a per-thread setting: other threads, a user's own OpenMP included, are not affected)
// and puts the previous value back. It looks the runtime up in the process (no link to it):
// without an OpenMP runtime loaded it does nothing.
namespace dampbound::detail {

class SerialOpenMp {
 public:
  SerialOpenMp();
  ~SerialOpenMp();
  SerialOpenMp(const SerialOpenMp&) = delete;
  SerialOpenMp& operator=(const SerialOpenMp&) = delete;

  /// True when an OpenMP runtime (libgomp) is loaded in this process and the guard acts.
  static bool active();
  /// The calling thread's max-active-levels (-1 without a runtime): for tests.
  static int max_active_levels();

 private:
  int previous_ = -1;
};

}  // namespace dampbound::detail
