#include <rrlab/storage/disk_reserve.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>

namespace rrlab::storage {

DiskReserve::DiskReserve(std::string path, std::int64_t bytes)
    : path_(std::move(path)), bytes_(std::max<std::int64_t>(bytes, 0)), disabled_(bytes <= 0) {
  struct stat existing {};
  if (!disabled_ && ::stat(path_.c_str(), &existing) == 0)  // kept from a run before (a restart)
    size_ = std::min<std::int64_t>(existing.st_size, bytes_);
  take();
}

bool DiskReserve::take() {
  std::lock_guard lock(mutex_);
  if (disabled_ || size_ == bytes_) return true;
  const int fd = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0600);
  if (fd < 0) {
    disabled_ = errno != ENOSPC && errno != EDQUOT;  // a read-only directory: no reserve here, ever
    return disabled_;
  }
  // allocated blocks, not a sparse file: the room is really taken
  const int error = ::posix_fallocate(fd, 0, bytes_);
  if (error == 0) {
    size_ = bytes_;
  } else {
    // what a failed allocation took goes back: the file keeps the room it had
    if (::ftruncate(fd, size_) != 0) size_ = 0;
    disabled_ = error != ENOSPC && error != EDQUOT;
  }
  ::close(fd);
  if (size_ == 0) std::remove(path_.c_str());
  return size_ == bytes_ || disabled_;
}

bool DiskReserve::release() {
  std::lock_guard lock(mutex_);
  if (size_ == 0) return false;
  const std::int64_t smaller = std::max<std::int64_t>(0, size_ - kStepBytes);
  if (smaller == 0) {
    std::remove(path_.c_str());
  } else if (::truncate(path_.c_str(), smaller) != 0) {
    std::remove(path_.c_str());  // the file cannot shrink: all of it goes
    size_ = 0;
    return true;
  }
  size_ = smaller;
  return true;
}

}  // namespace rrlab::storage
