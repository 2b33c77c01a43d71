// A database on a disk that is really full: a tmpfs of a few MiB mounted in
// a mount namespace of this test process alone (root, or a user namespace
// where the kernel allows one). Before the reserve, a DELETE on a full disk
// failed with storage_full (its journal needs room), also after a restart,
// so the documented remedy (delete runs) did not work.
#include <gtest/gtest.h>

#include <string>

#include "support/small_disk.hpp"

#include <rrlab/storage/database.hpp>
#include <rrlab/storage/disk_reserve.hpp>
#include <rrlab/storage/run_store.hpp>

#include "temp_store_test.hpp"

namespace rrlab::storage {
namespace {

using test::fill_with_a_file;
using test::SmallDisk;

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
