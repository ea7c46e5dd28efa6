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
// The guard does two things while it lives:
// - it sets OpenMP's max-active-levels to 0 for the calling thread (in libgomp since GCC 11 a
//   per-thread setting: other threads, a user's own OpenMP included, are not affected) and
//   puts the previous value back;
// - outside any OpenMP region (omp_get_level() == 0), the parallel regions this thread enters
//   run as plain calls. Even a team of one ends in libgomp with a barrier whose last thread
//   makes a futex system call, and CHOLMOD enters a region several times per supernode:
//   about 190 000 system calls per factorisation of the 200 x 200 plane's matrix, a third of
//   its time. dampbound defines libgomp's entry point GOMP_parallel (the one CHOLMOD calls)
//   for that: in a guarded thread at level 0 it calls the region's body once, which then sees
//   what a team of one shows it (omp_get_num_threads() 1, omp_get_thread_num() 0); every
//   other call goes on to libgomp's own GOMP_parallel unchanged.
//
// It looks the runtime up in the process (no link to it): without an OpenMP runtime loaded it
// does nothing.
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
  /// How many parallel regions the calling thread has run as plain calls: for tests.
  static long inline_regions();

 private:
  int previous_ = -1;
};

}  // namespace dampbound::detail
