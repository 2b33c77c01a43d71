// A full disk and a read-only database (RunStore's write faults, the probe
// write, FrameWriter's per-run failures), the total of stored frame bytes and
// the cap on stored scenarios.
#include <gtest/gtest.h>
#include <sqlite3.h>
#include <stdlib.h>

#include <filesystem>
#include <string>

#include <rrlab/storage/database.hpp>
#include <rrlab/storage/frame_writer.hpp>
#include <rrlab/storage/run_store.hpp>

#include "temp_store_test.hpp"

namespace rrlab::storage {
namespace {

class RunStoreFaults : public TempStoreTest {
 protected:
  // `count` frames of `bytes` bytes each for run `run`, from seq `first`.
  static std::vector<std::pair<std::int64_t, StoredFrame>> frames(std::int64_t run, int count, size_t bytes,
                                                                   std::int64_t first = 0) {
    std::vector<std::pair<std::int64_t, StoredFrame>> out;
    for (int i = 0; i < count; ++i) {
      StoredFrame f;
      f.seq = first + i;
      f.step = first + i;
      f.data = std::string(bytes, char('a' + i % 26));
      out.emplace_back(run, f);
    }
    return out;
  }
  static std::int64_t page_count(const std::string& path) {
    Database db(path);
    Statement s = db.prepare("PRAGMA page_count");
    s.step();
    return s.column_int(0);
  }
};

TEST_F(RunStoreFaults, SqliteCodesMapToFaults) {
  EXPECT_EQ(fault_of(SQLITE_FULL), StorageFault::full);
  EXPECT_EQ(fault_of(SQLITE_READONLY), StorageFault::readonly);
  EXPECT_EQ(fault_of(SQLITE_READONLY_DBMOVED), StorageFault::readonly);
  EXPECT_EQ(fault_of(SQLITE_IOERR_WRITE, ENOSPC), StorageFault::full);
  EXPECT_EQ(fault_of(SQLITE_IOERR_WRITE, EIO), StorageFault::other);
  EXPECT_EQ(fault_of(SQLITE_CONSTRAINT), StorageFault::other);
}

TEST_F(RunStoreFaults, TotalFrameBytesIsCountedAtOpenAndKeptCurrent) {
  std::int64_t a = 0, b = 0;
  {
    RunStore store(path_);
    EXPECT_EQ(store.total_frame_bytes(), 0);
    a = store.create_run(new_run());
    b = store.create_run(new_run());
    store.add_frames(frames(a, 10, 100));
    store.add_frames(frames(b, 5, 40));
    EXPECT_EQ(store.total_frame_bytes(), 10 * 100 + 5 * 40);
    FinishedRun finished{new_run(), "{}", std::nullopt, {}, {}};
    for (auto& [run, f] : frames(0, 3, 7)) finished.frames.push_back(f);
    ASSERT_TRUE(store.add_sweep_run(finished, {"s", "k", "sk", "ck", "file", true}));
    EXPECT_EQ(store.total_frame_bytes(), 1200 + 21);
  }
  RunStore reopened(path_);
  EXPECT_EQ(reopened.total_frame_bytes(), 1221);  // SUM(frame_bytes) at open
  ASSERT_TRUE(reopened.delete_run(a));
  EXPECT_EQ(reopened.total_frame_bytes(), 221);
  ASSERT_FALSE(reopened.delete_run(a));
  EXPECT_EQ(reopened.total_frame_bytes(), 221);
}

// PRAGMA max_page_count as a full disk: the failed write is typed and
// recorded, what was stored before is intact, reads work, and the fault
// lasts until a probe write succeeds (after a delete freed pages).
TEST_F(RunStoreFaults, AFullDatabaseIsATypedRecordedFaultUntilAProbeSucceeds) {
  RunStore store(path_);
  const std::int64_t kept = store.create_run(new_run());
  store.add_frames(frames(kept, 50, 500));
  store.finish_run(kept, "completed", "{}");
  const std::int64_t filler = store.create_run(new_run());
  store.add_frames(frames(filler, 2400, 500));  // about 300 pages, freed by its deletion below
  store.set_max_page_count(page_count(path_) + 2);
  EXPECT_FALSE(store.write_fault());

  const std::int64_t big = store.create_run(new_run());
  try {
    store.add_frames(frames(big, 400, 500));
    FAIL() << "200 kB into 2 free pages was accepted";
  } catch (const StorageError& e) {
    EXPECT_EQ(e.fault(), StorageFault::full) << e.what();
  }
  ASSERT_TRUE(store.write_fault());
  EXPECT_EQ(store.write_fault()->fault, StorageFault::full);
  EXPECT_FALSE(store.probe_write());
  EXPECT_TRUE(store.write_fault());

  // nothing of the failed batch, everything of before; reads work
  EXPECT_EQ(store.run(big)->frames, 0);
  EXPECT_EQ(store.run(kept)->frames, 50);
  int read = 0;
  store.frames(kept, 0, 49, 1, [&](const StoredFrame& f) {
    EXPECT_EQ(f.data, std::string(500, char('a' + f.seq % 26)));
    ++read;
    return true;
  });
  EXPECT_EQ(read, 50);
  EXPECT_EQ(store.total_frame_bytes(), 50 * 500 + 2400 * 500);
  EXPECT_EQ(store.integrity_check(), "ok");

  ASSERT_TRUE(store.delete_run(filler));  // a delete frees pages (needs none): room for the 1 MiB probe
  EXPECT_TRUE(store.probe_write());
  EXPECT_FALSE(store.write_fault());
  store.add_frames(frames(big, 20, 500));
  EXPECT_EQ(store.run(big)->frames, 20);
  EXPECT_EQ(store.integrity_check(), "ok");
}

TEST_F(RunStoreFaults, AReadOnlyDatabaseIsATypedFault) {
  {
    RunStore store(path_);
    store.create_run(new_run());
  }
  Database db(path_);
  db.exec("PRAGMA query_only=ON");  // SQLITE_READONLY, as a file opened read-only
  try {
    db.exec("INSERT INTO scenarios(name, json, created) VALUES ('x', '{}', 'now')");
    FAIL() << "a write to a query_only connection was accepted";
  } catch (const StorageError& e) {
    EXPECT_EQ(e.fault(), StorageFault::readonly) << e.what();
  }
  try {
    db.prepare("UPDATE runs SET status = 'x'").step();
    FAIL() << "a write to a query_only connection was accepted";
  } catch (const StorageError& e) {
    EXPECT_EQ(e.fault(), StorageFault::readonly) << e.what();
  }
}

// A failed batch fails its runs: their later frames are dropped (the stored
// frames stay a gap-free prefix); other runs' frames are still written.
TEST_F(RunStoreFaults, FrameWriterReportsAFailedRunAndDropsItsLaterFrames) {
  RunStore store(path_);
  const std::int64_t run = store.create_run(new_run());
  FrameWriter writer(store, 64, 16);
  for (auto& [id, f] : frames(run, 16, 100)) writer.push(id, std::move(f));
  writer.flush();
  EXPECT_FALSE(writer.run_error(run));
  EXPECT_EQ(writer.failures(), 0u);
  store.set_max_page_count(page_count(path_));
  for (auto& [id, f] : frames(run, 16, 4000, 16)) writer.push(id, std::move(f));
  writer.flush();
  ASSERT_TRUE(writer.run_error(run));
  EXPECT_NE(writer.run_error(run)->find("full"), std::string::npos) << *writer.run_error(run);
  EXPECT_EQ(writer.failures(), 1u);
  EXPECT_EQ(writer.queued_bytes(), 0);

  store.set_max_page_count(1 << 30);  // room again: the failed run still stores nothing more
  for (auto& [id, f] : frames(run, 4, 100, 32)) writer.push(id, std::move(f));
  const std::int64_t other = store.create_run(new_run());
  for (auto& [id, f] : frames(other, 4, 100)) writer.push(id, std::move(f));
  writer.flush();
  EXPECT_EQ(store.run(run)->frames, 16);
  EXPECT_EQ(store.run(other)->frames, 4);
  EXPECT_EQ(writer.failures(), 1u);
}

TEST_F(RunStoreFaults, StoredScenariosAreCapped) {
  RunStore store(path_);
  EXPECT_EQ(store.put_scenario("a", "{}", 2), PutScenario::added);
  EXPECT_EQ(store.put_scenario("a", "{}", 2), PutScenario::exists);
  EXPECT_EQ(store.put_scenario("b", "{}", 2), PutScenario::added);
  EXPECT_EQ(store.put_scenario("c", "{}", 2), PutScenario::full);
  EXPECT_EQ(store.put_scenario("a", "{}", 2), PutScenario::exists);  // a name that exists is named as such
  EXPECT_EQ(store.scenario_count(), 2);
  EXPECT_FALSE(store.scenario("c"));
}

}  // namespace
}  // namespace rrlab::storage
