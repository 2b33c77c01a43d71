// Background threads (sweeps, exports) run below the I/O threads and live
// runs: their nice value is raised relative to the thread that starts them,
// so that a server started at nice 19 does not have them outrank its own
// I/O (absolute values 10 and 5 did).
#pragma once

namespace rrlab::server {

// Raises the calling thread's nice value by `steps` (Linux: per thread, and
// inherited by the threads it starts), up to 19. Returns the new value.
int lower_thread_priority(int steps);

}  // namespace rrlab::server
