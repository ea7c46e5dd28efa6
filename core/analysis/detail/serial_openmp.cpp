#include "core/analysis/detail/serial_openmp.hpp"

#include <dlfcn.h>

namespace dampbound::detail {
namespace {

/// The OpenMP routines, found once: in the global scope (a program linked to CHOLMOD), else
/// in libgomp if something loaded it privately (a Python extension module).
struct OpenMpApi {
  int (*get_levels)() = nullptr;
  void (*set_levels)(int) = nullptr;
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
    if (a.get_levels == nullptr || a.set_levels == nullptr) a = OpenMpApi{};
    return a;
  }();
  return found;
}

}  // namespace

SerialOpenMp::SerialOpenMp() {
  if (!active()) return;
  previous_ = api().get_levels();
  api().set_levels(0);
}

SerialOpenMp::~SerialOpenMp() {
  if (previous_ >= 0) api().set_levels(previous_);
}

bool SerialOpenMp::active() { return api().set_levels != nullptr; }

int SerialOpenMp::max_active_levels() { return active() ? api().get_levels() : -1; }

}  // namespace dampbound::detail
