#pragma once
// CHOLMOD's OpenMP loops, run on the calling thread alone while it factors or solves.
//
// Debian's libcholmod (SuiteSparse 5.12) is built with OpenMP and asks for
// CHOLMOD_OMP_NUM_THREADS = 4 threads in its loops (scattering A into a supernode, clearing
// blocks), whatever the machine. Those loops are small: waking and parking threads for them
// costs more than they do (docs/performance.md). The numeric work is in the BLAS, which this
// does not touch.
//
// While the guard lives, OpenMP's max-active-levels is 0 for the calling thread
// (omp_set_max_active_levels, OpenMP 5.1 section 3.2.15; in libgomp since GCC 11 a per-thread
// setting): every region CHOLMOD enters runs as a team of one on that thread. Other threads,
// a user's own OpenMP included, keep their setting and their teams; the previous value is put
// back when the guard ends. dampbound defines no symbol of the OpenMP runtime: a program that
// loads it keeps libgomp's own entry points (tests/build/openmp_host.sh checks both).
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

 private:
  int previous_ = -1;
};

}  // namespace dampbound::detail
