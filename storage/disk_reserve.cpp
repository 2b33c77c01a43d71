#include "storage/disk_reserve.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>

namespace rrlab::storage {

DiskReserve::DiskReserve(std::string path, std::int64_t bytes)
    : path_(std::move(path)), bytes_(bytes), disabled_(bytes <= 0) {
  take();
}

bool DiskReserve::take() {
  std::lock_guard lock(mutex_);
  if (held_ || disabled_) return true;
  const int fd = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0600);
  if (fd < 0) {
    disabled_ = errno != ENOSPC && errno != EDQUOT;  // a read-only directory: no reserve here, ever
    return disabled_;
  }
  // allocated blocks, not a sparse file: the room is really taken
  const int error = ::posix_fallocate(fd, 0, bytes_);
  ::close(fd);
  held_ = error == 0;
  if (!held_) {
    std::remove(path_.c_str());
    disabled_ = error != ENOSPC && error != EDQUOT;
  }
  return held_ || disabled_;
}

bool DiskReserve::release() {
  std::lock_guard lock(mutex_);
  if (!held_) return false;
  held_ = false;
  return std::remove(path_.c_str()) == 0;
}

}  // namespace rrlab::storage
