#include <rrlab/server/app/thread_priority.hpp>

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>

namespace rrlab::server {

int lower_thread_priority(int steps) {
  const auto thread = static_cast<id_t>(syscall(SYS_gettid));
  errno = 0;
  const int now = getpriority(PRIO_PROCESS, thread);  // -1 is a valid value: errno tells a failure
  if (errno != 0) return now;
  const int lowered = std::min(19, now + steps);
  setpriority(PRIO_PROCESS, thread, lowered);
  return getpriority(PRIO_PROCESS, thread);
}

}  // namespace rrlab::server
