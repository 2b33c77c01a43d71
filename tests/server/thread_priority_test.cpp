// Background threads lower their priority relative to their starter: under a
// server started at nice 19 they stay at 19 (absolute 10 and 5 outranked it).
#include <rrlab/server/app/thread_priority.hpp>

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <thread>

namespace rrlab::testing {
namespace {

int thread_nice() { return getpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid))); }

// In a thread of its own: nice values are per thread on Linux.
int lowered_from(int start, int steps) {
  int result = -100;
  std::thread([&] {
    setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), start);
    if (thread_nice() != start) return;  // not allowed to set it here: leave -100
    result = server::lower_thread_priority(steps);
  }).join();
  return result;
}

TEST(ThreadPriority, LowersRelativeToTheStartingThread) {
  EXPECT_EQ(lowered_from(0, 10), 10);
  EXPECT_EQ(lowered_from(5, 5), 10);
  EXPECT_EQ(lowered_from(15, 10), 19);  // capped: never above the lowest priority
  EXPECT_EQ(lowered_from(19, 5), 19);   // a server at nice 19: its sweeps and exports do not outrank it
}

}  // namespace
}  // namespace rrlab::testing
