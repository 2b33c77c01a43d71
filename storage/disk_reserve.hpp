// Room kept on the database's disk for deleting runs: a file beside the
// database (DB-reserve) of a few MiB that is given back when a delete meets a
// full disk, so that the delete's journal has room and the documented remedy
// for a full disk (delete runs) works; taken again once the disk has room.
// Until it is, the disk counts as full for new writes (RunStore::probe_write):
// the room a delete freed is not eaten by the next run. Where no file can be
// made (a read-only directory) there is no reserve and nothing waits on it.
#pragma once

#include <cstdint>
#include <mutex>
#include <string>

namespace rrlab::storage {

class DiskReserve {
 public:
  static constexpr std::int64_t kDefaultBytes = 8 << 20;

  // Takes the room at once if it can (an existing reserve file is kept).
  DiskReserve(std::string path, std::int64_t bytes);
  bool held() {
    std::lock_guard lock(mutex_);
    return held_;
  }
  // Gives the room back (removes the file); false when there was none.
  bool release();
  // Takes the room again if the disk has it; true when held, or when this
  // directory can have none.
  bool take();

 private:
  std::mutex mutex_;  // a delete may release while a probe takes
  std::string path_;
  std::int64_t bytes_;
  bool held_ = false, disabled_ = false;
};

}  // namespace rrlab::storage
