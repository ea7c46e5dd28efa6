#include "ui/worker_priority.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <cerrno>

namespace dampbound::ui {

bool lower_worker_priority() {
  // On Linux PRIO_PROCESS with a thread id sets that thread's nice value alone.
  const id_t self = static_cast<id_t>(gettid());
  errno = 0;
  const int now = getpriority(PRIO_PROCESS, self);
  if (errno != 0) return false;
  if (now >= kWorkerNice) return true;
  return setpriority(PRIO_PROCESS, self, kWorkerNice) == 0;
}

int worker_nice() {
  errno = 0;
  return getpriority(PRIO_PROCESS, static_cast<id_t>(gettid()));
}

}  // namespace dampbound::ui
