// The frame writer (storage/frame_writer.hpp): input events share the frames'
// queue and transactions, never wait for room, and say when they are stored.
#include <rrlab/storage/frame_writer.hpp>

#include <chrono>
#include <future>

#include "temp_store_test.hpp"

namespace rrlab::storage {
namespace {

class FrameWriterTest : public TempStoreTest {};

StoredFrame frame(std::int64_t seq) { return {seq, seq, 0.01 * double(seq), 0, 1, false, std::string(16, 'x')}; }

// Waits (bounded, however slow the machine) for a completion to settle.
Outcome settled(const std::shared_ptr<Completion>& done) {
  auto promise = std::make_shared<std::promise<Outcome>>();
  auto future = promise->get_future();
  done->then([promise](const Outcome& o) { promise->set_value(o); });
  EXPECT_EQ(future.wait_for(std::chrono::seconds(60)), std::future_status::ready);
  return future.get();
}

TEST_F(FrameWriterTest, AnEventSettlesOnceCommittedInQueueOrder) {
  RunStore store(path_);
  const auto run = store.create_run(new_run());
  FrameWriter writer(store);
  for (std::int64_t seq = 0; seq < 3000; ++seq) writer.push(run, frame(seq));
  auto first = std::make_shared<Completion>(), second = std::make_shared<Completion>();
  writer.push_event(run, {3000, 3000, "params", R"({"gain":1})"}, first);
  writer.push_event(run, {3000, 3000, "params", R"({"gain":2})"});  // nobody waits on this one
  writer.push_event(run, {3001, 3001, "reset", "{}"}, second);
  const Outcome outcome = settled(second);
  EXPECT_TRUE(outcome.ok()) << outcome.error;
  EXPECT_TRUE(first->settled());  // one queue: what was pushed before is committed too
  // committed with (or after) the frames queued before them, in their order
  EXPECT_EQ(store.run(run)->frames, 3000);
  const std::vector<StoredEvent> events = store.events(run);
  ASSERT_EQ(events.size(), 3u);
  EXPECT_EQ(events[0].payload_json, R"({"gain":1})");
  EXPECT_EQ(events[1].payload_json, R"({"gain":2})");
  EXPECT_EQ(events[2].kind, "reset");
}

// The queue holds at most `capacity` frames: a full queue makes push() wait,
// and an event still goes in (an I/O thread must never wait for SQLite).
TEST_F(FrameWriterTest, EventsDoNotWaitForRoom) {
  RunStore store(path_);
  const auto run = store.create_run(new_run());
  FrameWriter writer(store, /*capacity=*/4, /*batch=*/2);
  for (std::int64_t seq = 0; seq < 4; ++seq) writer.push(run, frame(seq));
  auto done = std::make_shared<Completion>();
  for (int i = 0; i < 100; ++i) writer.push_event(run, {4, 4, "params", "{}"}, i == 99 ? done : nullptr);
  EXPECT_TRUE(settled(done).ok());
  writer.flush();
  EXPECT_EQ(store.events(run).size(), 100u);
}

// A run whose frames failed stores nothing later: its events settle with the error.
TEST_F(FrameWriterTest, AnEventOfAFailedRunSettlesWithTheError) {
  RunStore store(path_);
  const auto run = store.create_run(new_run());
  FrameWriter writer(store);
  writer.push(run, frame(0));
  writer.push(run, frame(0));  // the same seq again: the batch fails (primary key)
  writer.flush();
  ASSERT_TRUE(writer.run_error(run));
  auto done = std::make_shared<Completion>();
  writer.push_event(run, {1, 1, "params", "{}"}, done);
  const Outcome outcome = settled(done);
  EXPECT_FALSE(outcome.ok());
  EXPECT_EQ(outcome.error, *writer.run_error(run));
  EXPECT_TRUE(store.events(run).empty());
}

}  // namespace
}  // namespace rrlab::storage
