// Sweep progress on stderr: on a terminal one line redrawn in place
// (bar, done/total, runs/s, ETA); otherwise a plain line every 5 s or every
// 10 % of the runs. Wall-clock time is used here only, never in results.
#pragma once

#include <chrono>
#include <cstddef>
#include <mutex>
#include <ostream>

namespace rrlab::sweep {

class SweepProgress {
 public:
  // `total` runs in this invocation's shard, `already` of them stored before.
  SweepProgress(std::ostream& out, bool terminal, size_t total, size_t already);
  void run_done();  // thread-safe
  void finish();    // the last line (and a newline on a terminal)

 private:
  void draw(bool last);

  std::ostream& out_;
  const bool terminal_;
  const size_t total_, already_;
  size_t done_ = 0, drawn_ = 0, next_tenth_ = 1;
  std::chrono::steady_clock::time_point start_, last_draw_;
  std::mutex mutex_;
};

}  // namespace rrlab::sweep
