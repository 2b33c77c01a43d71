// A database written by an older rrlab opens in this one: the committed
// fixture is a real version-1 file (batch runs, a sweep, a live run with
// events), dumped as SQL by sqlite3.
#include <rrlab/storage/migrations.hpp>

#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <rrlab/storage/database.hpp>
#include <rrlab/storage/frame_codec.hpp>
#include <rrlab/storage/run_store.hpp>

#include "temp_store_test.hpp"

namespace rrlab::storage {
namespace {

class MigrationsTest : public TempStoreTest {
 protected:

  void write_fixture(const std::string& name) {
    std::ifstream in(std::string(RRLAB_SOURCE_DIR) + "/tests/storage/fixtures/" + name);
    ASSERT_TRUE(in) << name;
    std::stringstream sql;
    sql << in.rdbuf();
    Database db(path_);
    db.exec(sql.str());
  }
  std::int64_t scalar(const std::string& sql) {
    Database db(path_);
    Statement s = db.prepare(sql);
    EXPECT_TRUE(s.step()) << sql;
    return s.column_int(0);
  }
};

TEST_F(MigrationsTest, AVersionOneDatabaseOpensWithEveryRunIntact) {
  write_fixture("schema_v1.sql");
  const std::int64_t frames_before = scalar("SELECT COUNT(*) FROM frames");
  const std::int64_t bytes_before = scalar("SELECT SUM(length(data)) FROM frames");
  ASSERT_EQ(frames_before, 65);  // 20 + 15 + 10 + 10 + 10
  {
    RunStore store(path_);
    EXPECT_EQ(store.migrated_from(), 1);
    const std::vector<RunRecord> runs = store.runs({});
    ASSERT_EQ(runs.size(), 5u);
    std::int64_t bytes = 0, frames = 0;
    for (const RunRecord& r : runs) {
      bytes += r.frame_bytes;
      frames += r.frames;
      // every stored frame still decodes with this rrlab's codec
      std::int64_t seen = 0;
      store.frames(r.id, 0, r.frames - 1, 1, [&](const StoredFrame& f) {
        const Frame frame = unpack_frame(f.data);
        EXPECT_EQ(frame.step, f.step);
        EXPECT_EQ(frame.q.size(), r.dof);
        ++seen;
        return true;
      });
      EXPECT_EQ(seen, r.frames);
    }
    EXPECT_EQ(frames, frames_before);
    EXPECT_EQ(bytes, bytes_before);  // counted by the migration
    EXPECT_EQ(store.events(5).size(), 2u);  // the live run's joystick and params
    EXPECT_EQ(store.sweep_runs("v1-fixture").size(), 2u);
    // and it takes new runs with the new column
    EXPECT_GT(store.create_run(new_run()), 5);
  }
  EXPECT_EQ(scalar("SELECT version FROM schema_version"), current_schema_version());
  RunStore again(path_);  // a second open has nothing to migrate
  EXPECT_EQ(again.migrated_from(), current_schema_version());
}

// A version-2 file (an older rrlab's sweep of 4 runs and a stored run) gains
// the sweep runs' failure columns, empty for the runs it had.
TEST_F(MigrationsTest, AVersionTwoDatabaseOpensWithItsSweepRuns) {
  write_fixture("schema_v2.sql");
  ASSERT_EQ(scalar("SELECT version FROM schema_version"), 2);
  {
    RunStore store(path_);
    EXPECT_EQ(store.migrated_from(), 2);
    const std::vector<SweepRunEntry> runs = store.sweep_runs("v2-fixture");
    ASSERT_EQ(runs.size(), 4u);
    for (const SweepRunEntry& e : runs) {
      EXPECT_FALSE(e.row.failure_mode);
      EXPECT_FALSE(e.row.failure_t);
      EXPECT_TRUE(e.summary_json);
    }
    EXPECT_EQ(store.runs({}).size(), 5u);
    EXPECT_EQ(scalar("SELECT COUNT(*) FROM frames"), 5);
  }
  EXPECT_EQ(scalar("SELECT version FROM schema_version"), current_schema_version());
}

TEST_F(MigrationsTest, ANewFileGetsTheCurrentSchema) {
  RunStore store(path_);
  EXPECT_EQ(store.migrated_from(), 0);
  EXPECT_EQ(scalar("SELECT version FROM schema_version"), current_schema_version());
}

TEST_F(MigrationsTest, ADatabaseFromANewerRrlabIsRefusedUntouched) {
  write_fixture("schema_v1.sql");
  {
    Database db(path_);
    db.exec("UPDATE schema_version SET version = 99");
  }
  try {
    RunStore store(path_);
    FAIL() << "opened";
  } catch (const StorageError& e) {
    EXPECT_NE(std::string(e.what()).find("newer rrlab (schema version 99"), std::string::npos) << e.what();
  }
  EXPECT_EQ(scalar("SELECT version FROM schema_version"), 99);
  EXPECT_EQ(scalar("SELECT COUNT(*) FROM frames"), 65);
}

TEST_F(MigrationsTest, AFailedMigrationLeavesTheFileAsItWas) {
  write_fixture("schema_v1.sql");
  {
    Database db(path_);  // a column the migration is about to add makes it fail
    db.exec("ALTER TABLE runs ADD COLUMN frame_bytes INTEGER");
  }
  try {
    RunStore store(path_);
    FAIL() << "opened";
  } catch (const StorageError& e) {
    EXPECT_NE(std::string(e.what()).find("migrating the database to schema version 2"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(scalar("SELECT version FROM schema_version"), 1);
  EXPECT_EQ(scalar("SELECT COUNT(*) FROM runs"), 5);
}

TEST(Migrations, StepsAreInOrderAndEndAtTheCurrentVersion) {
  int expected = 2;
  for (const Migration* m = migrations_begin(); m != migrations_end(); ++m) EXPECT_EQ(m->to_version, expected++);
  EXPECT_EQ(expected - 1, current_schema_version());
}

}  // namespace
}  // namespace rrlab::storage
