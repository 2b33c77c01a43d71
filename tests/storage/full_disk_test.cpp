// A database on a disk that is really full: a tmpfs of a few MiB mounted in
// a mount namespace of this test process alone (root, or a user namespace
// where the kernel allows one). Before the reserve, a DELETE on a full disk
// failed with storage_full (its journal needs room), also after a restart,
// so the documented remedy (delete runs) did not work.
#include <gtest/gtest.h>
#include <sched.h>
#include <sys/mount.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "storage/database.hpp"
#include "storage/disk_reserve.hpp"
#include "storage/run_store.hpp"
#include "temp_store_test.hpp"

namespace rrlab::storage {
namespace {

// A private tmpfs of `mib` MiB at a new temporary directory.
class SmallDisk {
 public:
  explicit SmallDisk(int mib) {
    const uid_t uid = getuid();
    const gid_t gid = getgid();
    if (unshare(uid == 0 ? CLONE_NEWNS : CLONE_NEWNS | CLONE_NEWUSER) != 0) {
      error_ = std::string("unshare: ") + std::strerror(errno);
      return;
    }
    if (uid != 0) {  // map ourselves to root in the new user namespace
      std::ofstream("/proc/self/setgroups") << "deny";
      std::ofstream("/proc/self/uid_map") << "0 " << uid << " 1";
      std::ofstream("/proc/self/gid_map") << "0 " << gid << " 1";
    }
    mount("none", "/", nullptr, MS_REC | MS_PRIVATE, nullptr);  // nothing propagates out
    std::string pattern = "/tmp/rrlab-small-disk-XXXXXX";
    if (!mkdtemp(pattern.data())) {
      error_ = "mkdtemp failed";
      return;
    }
    dir_ = pattern;
    const std::string options = "size=" + std::to_string(mib) + "m";
    if (mount("tmpfs", dir_.c_str(), "tmpfs", 0, options.c_str()) != 0)
      error_ = std::string("mount tmpfs: ") + std::strerror(errno);
  }
  ~SmallDisk() {
    if (!dir_.empty()) {
      umount2(dir_.c_str(), MNT_DETACH);
      std::filesystem::remove_all(dir_);
    }
  }
  const std::string& error() const { return error_; }
  std::string path(const std::string& name) const { return dir_ + "/" + name; }
  std::int64_t free_bytes() const {
    struct statvfs s {};
    statvfs(dir_.c_str(), &s);
    return std::int64_t(s.f_bavail) * std::int64_t(s.f_frsize);
  }

 private:
  std::string dir_, error_;
};

std::vector<std::pair<std::int64_t, StoredFrame>> frames(std::int64_t run, int count, std::int64_t first) {
  std::vector<std::pair<std::int64_t, StoredFrame>> out;
  for (int i = 0; i < count; ++i) {
    StoredFrame f;
    f.seq = f.step = first + i;
    f.data = std::string(1000, char('a' + (first + i) % 26));
    out.emplace_back(run, f);
  }
  return out;
}

// Frames of 1 KB in batches of 256 until the disk is full; how many were stored.
std::int64_t fill(RunStore& store, std::int64_t run) {
  std::int64_t stored = 0;
  for (;;) {
    try {
      store.add_frames(frames(run, 256, stored));
    } catch (const StorageError& e) {
      EXPECT_EQ(e.fault(), StorageFault::full) << e.what();
      return stored;
    }
    stored += 256;
  }
}

// Writes a file until the disk refuses more: what else filled the disk.
void fill_with_a_file(const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  const std::string block(64 << 10, 'x');
  while (out.write(block.data(), std::streamsize(block.size())) && out.flush()) {
  }
}

class FullDisk : public TempStoreTest {};

TEST_F(FullDisk, DeletingRunsWorksAndTheSpaceComesBackAlsoAfterARestart) {
  SmallDisk disk(32);
  ASSERT_EQ(disk.error(), "") << "a tmpfs in a private mount namespace is needed for this test";
  const std::string db = disk.path("rrlab.db");
  std::int64_t small = 0, big = 0;
  {
    RunStore store(db, DiskReserve::kDefaultBytes);  // as the server opens it
    small = store.create_run(new_run());
    store.add_frames(frames(small, 100, 0));
    store.finish_run(small, "completed", "{}");
    big = store.create_run(new_run());
    EXPECT_GT(fill(store, big), 4000) << "the disk filled before a run of any size";
  }  // left "running": the restart marks it interrupted, which needs room too
  // the rest of the disk filled by something else; then a restart on the full disk
  fill_with_a_file(disk.path("other-data"));
  EXPECT_LT(disk.free_bytes(), 64 << 10);
  RunStore store(db, DiskReserve::kDefaultBytes);
  EXPECT_FALSE(store.probe_write());
  // the documented remedy: delete a run
  const std::int64_t free_before = disk.free_bytes();
  ASSERT_TRUE(store.delete_run(big));
  EXPECT_FALSE(store.run(big));
  ASSERT_TRUE(store.run(small));
  EXPECT_EQ(store.run(small)->frames, 100);
  EXPECT_GT(disk.free_bytes(), free_before + (4 << 20)) << "the deleted run's space did not come back to the disk";
  EXPECT_TRUE(store.probe_write()) << "still full after deleting the run that filled the disk";
  const std::int64_t again = store.create_run(new_run());
  EXPECT_NO_THROW(store.add_frames(frames(again, 1000, 0)));  // new runs fit again
  EXPECT_EQ(store.integrity_check(), "ok");
}

}  // namespace
}  // namespace rrlab::storage
