#include <rrlab/storage/run_store.hpp>

#include <gtest/gtest.h>
#include <stdlib.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include <rrlab/storage/database.hpp>
#include <rrlab/storage/frame_writer.hpp>

#include "temp_store_test.hpp"

namespace rrlab::storage {
namespace {

using RunStoreTest = TempStoreTest;

TEST_F(RunStoreTest, CreatesRunsAndFilters) {
  RunStore store(path_);
  const auto a = store.create_run(new_run("pinv"));
  const auto b = store.create_run(new_run("dls"));
  EXPECT_LT(a, b);
  EXPECT_EQ(store.run(a)->status, "running");
  store.finish_run(a, "completed", R"({"steps":3})");
  EXPECT_EQ(store.run(a)->status, "completed");
  EXPECT_EQ(*store.run(a)->summary_json, R"({"steps":3})");
  RunFilter filter;
  filter.method = "dls";
  ASSERT_EQ(store.runs(filter).size(), 1u);
  EXPECT_EQ(store.runs(filter)[0].id, b);
  EXPECT_FALSE(store.run(999).has_value());
  EXPECT_EQ(store.integrity_check(), "ok");
}

TEST_F(RunStoreTest, FramesAndEventsRoundTrip) {
  RunStore store(path_);
  const auto id = store.create_run(new_run());
  std::vector<std::pair<std::int64_t, StoredFrame>> batch;
  for (int i = 0; i < 10; ++i)
    batch.push_back({id, StoredFrame{i, i, 0.01 * i, 0.0, std::numeric_limits<double>::infinity(), false,
                                     std::string(8, char('a' + i))}});
  store.add_frames(batch);
  store.add_event(id, {3, 3, "params", R"({"gain":2})"});
  EXPECT_EQ(store.run(id)->frames, 10);
  std::vector<std::int64_t> seqs;
  store.frames(id, 2, 8, 3, [&](const StoredFrame& f) {
    seqs.push_back(f.seq);
    EXPECT_TRUE(std::isinf(f.min_distance));
    EXPECT_EQ(f.data, std::string(8, char('a' + f.seq)));
    return true;
  });
  EXPECT_EQ(seqs, (std::vector<std::int64_t>{2, 5, 8}));
  ASSERT_EQ(store.events(id).size(), 1u);
  EXPECT_EQ(store.events(id)[0].kind, "params");
}

TEST_F(RunStoreTest, DeletesARunWithItsFramesAndEventsOnly) {
  RunStore store(path_);
  const auto doomed = store.create_run(new_run()), kept = store.create_run(new_run());
  std::vector<std::pair<std::int64_t, StoredFrame>> batch;
  for (int i = 0; i < 5; ++i) {
    batch.push_back({doomed, StoredFrame{i, i, 0.01 * i, 0, 0, false, "d"}});
    batch.push_back({kept, StoredFrame{i, i, 0.01 * i, 0, 0, false, "k"}});
  }
  store.add_frames(batch);
  store.add_event(doomed, {1, 1, "params", "{}"});
  store.add_event(kept, {2, 2, "joystick", "{}"});

  EXPECT_TRUE(store.delete_run(doomed));
  EXPECT_FALSE(store.run(doomed).has_value());
  EXPECT_TRUE(store.events(doomed).empty());
  int doomed_frames = 0;
  store.frames(doomed, 0, 100, 1, [&](const StoredFrame&) { return ++doomed_frames, true; });
  EXPECT_EQ(doomed_frames, 0);
  // the other run is untouched
  EXPECT_EQ(store.run(kept)->frames, 5);
  ASSERT_EQ(store.events(kept).size(), 1u);
  EXPECT_EQ(store.events(kept)[0].kind, "joystick");
  EXPECT_EQ(store.runs({}).size(), 1u);
  // unknown (or already deleted) ids
  EXPECT_FALSE(store.delete_run(doomed));
  EXPECT_FALSE(store.delete_run(999));
  EXPECT_EQ(store.integrity_check(), "ok");
}

TEST_F(RunStoreTest, UnfinishedRunsAreMarkedInterruptedOnReopen) {
  std::int64_t done = 0, open = 0;
  {
    RunStore store(path_);
    done = store.create_run(new_run());
    store.finish_run(done, "completed", "{}");
    open = store.create_run(new_run());
  }
  RunStore reopened(path_);
  EXPECT_EQ(reopened.interrupted_at_open(), 1);
  EXPECT_EQ(reopened.run(open)->status, "interrupted");
  EXPECT_EQ(reopened.run(done)->status, "completed");
}

TEST_F(RunStoreTest, ScenariosAreUniqueByName) {
  RunStore store(path_);
  EXPECT_TRUE(store.put_scenario("mine", "{\"name\":\"mine\"}"));
  EXPECT_FALSE(store.put_scenario("mine", "{}"));
  EXPECT_EQ(*store.scenario("mine"), "{\"name\":\"mine\"}");
  EXPECT_EQ(store.scenario_names(), std::vector<std::string>{"mine"});
}

TEST_F(RunStoreTest, RejectsAFileThatIsNotADatabase) {
  { std::FILE* f = std::fopen(path_.c_str(), "w"); std::fputs("not a database, just text that is long enough to matter", f); std::fclose(f); }
  EXPECT_THROW(RunStore store(path_), StorageError);
}

TEST_F(RunStoreTest, FrameWriterCommitsEverythingOnFlush) {
  RunStore store(path_);
  const auto a = store.create_run(new_run()), b = store.create_run(new_run());
  {
    FrameWriter writer(store, 64, 16);  // a small queue: push() must wait, not drop
    for (int i = 0; i < 1000; ++i) {
      writer.push(a, StoredFrame{i, i, 0, 0, 0, false, "x"});
      writer.push(b, StoredFrame{i, i, 0, 0, 0, false, "y"});
    }
    writer.flush();
    EXPECT_EQ(store.run(a)->frames, 1000);
    EXPECT_EQ(store.run(b)->frames, 1000);
    EXPECT_EQ(writer.last_error(), "");
  }
}

}  // namespace
}  // namespace rrlab::storage
