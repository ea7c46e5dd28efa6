#include "core/analysis/detail/serial_openmp.hpp"

#include <dlfcn.h>

namespace dampbound::detail {
namespace {

/// The OpenMP routines, found once: in the global scope (a program linked to CHOLMOD), else
/// in libgomp if something loaded it privately (a Python extension module).
struct OpenMpApi {
  int (*get_levels)() = nullptr;
  void (*set_levels)(int) = nullptr;
  int (*level)() = nullptr;
};

const OpenMpApi& api() {
  static const OpenMpApi found = [] {
    OpenMpApi a;
    void* scope = RTLD_DEFAULT;  // (a null handle: the global scope)
    if (dlsym(scope, "omp_set_max_active_levels") == nullptr) {
      scope = dlopen("libgomp.so.1", RTLD_LAZY | RTLD_NOLOAD);  // null when not loaded
      if (scope == nullptr) return a;
    }
    // POSIX: a symbol's address converts to a function pointer through the object pointer.
    a.get_levels = reinterpret_cast<int (*)()>(dlsym(scope, "omp_get_max_active_levels"));
    a.set_levels = reinterpret_cast<void (*)(int)>(dlsym(scope, "omp_set_max_active_levels"));
    a.level = reinterpret_cast<int (*)()>(dlsym(scope, "omp_get_level"));
    if (a.get_levels == nullptr || a.set_levels == nullptr || a.level == nullptr) a = OpenMpApi{};
    return a;
  }();
  return found;
}

thread_local int t_guards = 0;  // SerialOpenMp guards alive on this thread
thread_local long t_inline_regions = 0;

}  // namespace

SerialOpenMp::SerialOpenMp() {
  ++t_guards;
  if (!active()) return;
  previous_ = api().get_levels();
  api().set_levels(0);
}

SerialOpenMp::~SerialOpenMp() {
  --t_guards;
  if (previous_ >= 0) api().set_levels(previous_);
}

bool SerialOpenMp::active() { return api().set_levels != nullptr; }

int SerialOpenMp::max_active_levels() { return active() ? api().get_levels() : -1; }

long SerialOpenMp::inline_regions() {
  return t_inline_regions;
}

namespace {

using Parallel = void (*)(void (*)(void*), void*, unsigned, unsigned);

/// libgomp's own GOMP_parallel: asked of libgomp itself (wherever it comes in the search
/// order), else the next definition after this one.
Parallel gomp_parallel() {
  static const Parallel real = [] {
    void* p = nullptr;
    // (The reference NOLOAD takes is kept, so the function stays for the process's life.)
    if (void* gomp = dlopen("libgomp.so.1", RTLD_LAZY | RTLD_NOLOAD))
      p = dlvsym(gomp, "GOMP_parallel", "GOMP_4.0");
    if (p == nullptr) p = dlvsym(RTLD_NEXT, "GOMP_parallel", "GOMP_4.0");
    if (p == nullptr) p = dlsym(RTLD_NEXT, "GOMP_parallel");
    return reinterpret_cast<Parallel>(p);
  }();
  return real;
}

/// A region entered here runs as a plain call: a guard lives on this thread and it is in no
/// other region (its body then sees a team of one).
bool inline_here() {
  return t_guards > 0 && api().level != nullptr && api().level() == 0;
}

}  // namespace
}  // namespace dampbound::detail

/// The entry point GCC emits for `#pragma omp parallel` (libgomp's ABI since GCC 4.9): see
/// serial_openmp.hpp. A region in a thread under SerialOpenMp, outside any other region, is
/// its body called once; so is every region if libgomp's own cannot be found (a valid team of
/// one). Otherwise libgomp's, with the same arguments.
extern "C" __attribute__((visibility("default"))) void GOMP_parallel(void (*fn)(void*), void* data,
                                                                     unsigned num_threads,
                                                                     unsigned flags) {
  using namespace dampbound::detail;
  const Parallel real = gomp_parallel();
  if (real != nullptr && !inline_here()) {
    real(fn, data, num_threads, flags);
    return;
  }
  ++t_inline_regions;
  fn(data);
}
