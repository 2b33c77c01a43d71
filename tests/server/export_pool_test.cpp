// app/export_pool.hpp: the budget of bytes that exports reserve, and the workers.
#include <rrlab/server/app/export_pool.hpp>

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <thread>

#include "support/eventually.hpp"

namespace rrlab::server {
namespace {

TEST(ExportPool, ReservationsStayWithinTheBudgetAndReturnWithTheirTickets) {
  ExportPool pool(1, 4 << 10);
  auto a = pool.reserve(2 << 10), b = pool.reserve(2 << 10);
  ASSERT_TRUE(a && b);
  EXPECT_EQ(pool.reserved(), std::size_t(4 << 10));
  EXPECT_FALSE(pool.reserve(1)) << "over the budget: the caller answers 503";
  a.reset();  // an export ended (or its connection closed)
  EXPECT_EQ(pool.reserved(), std::size_t(2 << 10));
  EXPECT_TRUE(pool.reserve(2 << 10));  // released again at once: a temporary
  EXPECT_EQ(pool.reserved(), std::size_t(2 << 10));
}

TEST(ExportPool, RunsTasksOnWorkersThatSurviveAFailingTask) {
  ExportPool pool(2, 1 << 20);
  std::promise<std::thread::id> ran;
  pool.post([&] { ran.set_value(std::this_thread::get_id()); });
  auto future = ran.get_future();
  ASSERT_EQ(future.wait_for(std::chrono::seconds(10)), std::future_status::ready);
  EXPECT_NE(future.get(), std::this_thread::get_id());
  std::atomic<int> failed_then_ran{0};
  pool.post([] { throw std::runtime_error("a failing task"); });  // a worker survives it
  std::promise<void> after;
  pool.post([&] { ++failed_then_ran; after.set_value(); });
  ASSERT_EQ(after.get_future().wait_for(std::chrono::seconds(10)), std::future_status::ready);
  EXPECT_EQ(failed_then_ran.load(), 1);
}

TEST(ExportPool, StopDropsQueuedTasksAndTheirReservations) {
  ExportPool pool(1, 1 << 20);
  std::promise<void> started, release;
  auto released = release.get_future().share();
  pool.post([&] {
    started.set_value();
    released.wait();
  });
  started.get_future().wait();
  auto ticket = pool.reserve(1000);
  bool ran = false;
  pool.post([&ran, ticket] { ran = true; });  // queued behind the busy worker, holding the reservation
  ticket.reset();
  EXPECT_EQ(pool.reserved(), 1000u);
  std::thread stopper([&] { pool.stop(); });
  // the worker is released only once stop() has begun, so it must drop the queued task
  const bool began = rrlab::test::eventually([&] { return pool.stopping(); }, std::chrono::seconds(60), "stop() to begin");
  release.set_value();
  stopper.join();
  ASSERT_TRUE(began);
  EXPECT_FALSE(ran);
  EXPECT_EQ(pool.reserved(), 0u);
  pool.post([&ran] { ran = true; });  // after stop: dropped
  EXPECT_FALSE(ran);
}

}  // namespace
}  // namespace rrlab::server
