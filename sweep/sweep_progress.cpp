#include <rrlab/sweep/sweep_progress.hpp>

#include <cstdio>
#include <string>

namespace rrlab::sweep {

SweepProgress::SweepProgress(std::ostream& out, bool terminal, size_t total, size_t already)
    : out_(out), terminal_(terminal), total_(total), already_(already), start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

void SweepProgress::run_done() {
  std::lock_guard lock(mutex_);
  ++done_;
  const auto now = std::chrono::steady_clock::now();
  const size_t todo = total_ - already_;
  const bool tenth = todo > 0 && done_ * 10 >= next_tenth_ * todo;
  if (tenth) next_tenth_ = done_ * 10 / todo + 1;
  if (terminal_ ? now - last_draw_ >= std::chrono::milliseconds(100) : (tenth || now - last_draw_ >= std::chrono::seconds(5)))
    draw(false);
}

void SweepProgress::finish() {
  std::lock_guard lock(mutex_);
  if (terminal_ || drawn_ != done_ || done_ == 0) draw(true);
}

void SweepProgress::draw(bool last) {
  last_draw_ = std::chrono::steady_clock::now();
  drawn_ = done_;
  const double seconds = std::chrono::duration<double>(last_draw_ - start_).count();
  const double rate = seconds > 0 ? double(done_) / seconds : 0;
  const size_t stored = already_ + done_;
  const size_t left = total_ > stored ? total_ - stored : 0;
  char numbers[160];
  if (rate > 0)
    std::snprintf(numbers, sizeof numbers, "%zu/%zu runs  %.1f runs/s  ETA %.0f s", stored, total_, rate, double(left) / rate);
  else
    std::snprintf(numbers, sizeof numbers, "%zu/%zu runs", stored, total_);
  if (terminal_) {
    constexpr int kWidth = 30;
    const int filled = total_ ? int(double(kWidth) * double(stored) / double(total_)) : kWidth;
    out_ << "\r\033[K[" << std::string(size_t(filled), '#') << std::string(size_t(kWidth - filled), ' ') << "] "
         << numbers << (last ? "\n" : "") << std::flush;
  } else {
    out_ << "rrlab: sweep: " << numbers << '\n' << std::flush;
  }
}

}  // namespace rrlab::sweep
