// Gives the allocator's free pages back to the system after a request that
// allocated a lot briefly (a large sweep spec checked, a report built): the
// server's resident memory returns to where it was instead of staying at the
// request's peak (glibc keeps freed memory in its arenas otherwise).
#pragma once

namespace rrlab::server {

void release_free_memory();

}  // namespace rrlab::server
