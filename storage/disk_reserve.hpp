// Room kept on the database's disk for deleting runs: a file beside the
// database (DB-reserve) of a few MiB that is given back a step (1 MiB) at a
// time when a write meets a full disk, so that a delete's journal has room
// and the documented remedy for a full disk (delete runs) works; taken again
// once the disk has room. Until it is whole again, the disk counts as full for
// new writes (RunStore::probe_write): the room a delete freed is not eaten by
// the next run. Given back in steps, so that opening the database on a full
// disk (a restart) uses only what its journal needs and leaves the rest for
// deletes. Where no file can be made (a read-only directory) there is no
// reserve and nothing waits on it.
#pragma once

#include <cstdint>
#include <mutex>
#include <string>

namespace rrlab::storage {

class DiskReserve {
 public:
  static constexpr std::int64_t kDefaultBytes = 8 << 20;
  static constexpr std::int64_t kStepBytes = 1 << 20;

  // Takes the room at once if it can (an existing reserve file is kept).
  DiskReserve(std::string path, std::int64_t bytes);
  // The whole reserve is held.
  bool held() {
    std::lock_guard lock(mutex_);
    return size_ == bytes_;
  }
  // Gives one step of the room back (shrinks or removes the file); false
  // when there was none left.
  bool release();
  // Takes the whole room again if the disk has it; true when held, or when
  // this directory can have none.
  bool take();

 private:
  std::mutex mutex_;  // a delete may release while a probe takes
  std::string path_;
  std::int64_t bytes_;
  std::int64_t size_ = 0;  // what the file holds now
  bool disabled_ = false;
};

}  // namespace rrlab::storage
