// Re-simulating a run that stored no frames compares nothing: the answer says
// so (identical null, compared false, a reason) instead of "identical: true".
#include "server_fixture.hpp"

namespace rrlab::testing {
namespace {

using nlohmann::json;

class NothingCompared : public ServerTest {};

TEST_F(NothingCompared, ResimulatingARunWithoutFramesSaysNothingWasCompared) {
  // started paused and stopped at once: no step was taken, no frame stored
  const std::int64_t id = start_live({{"scenario", small_scenario()}, {"paused", true}});
  const std::string base = "/api/runs/" + std::to_string(id);
  ASSERT_EQ(send("POST", base + "/control", {{"action", "stop"}}).status, 200);
  ASSERT_EQ(wait_ended(id)["frames"], 0);

  const HttpResult resim = send("POST", base + "/replay", {{"mode", "resimulate"}});
  ASSERT_EQ(resim.status, 200) << resim.body;
  const json verdict = resim.json();
  EXPECT_TRUE(verdict["identical"].is_null()) << verdict;
  EXPECT_EQ(verdict["compared"], false);
  EXPECT_EQ(verdict["frames_compared"], 0);
  EXPECT_EQ(verdict["reason"], "the run stored no frames: nothing to compare");
  EXPECT_EQ(verdict["source_run"], id);
}

TEST_F(NothingCompared, ARunWithFramesIsCompared) {
  const HttpResult batch = send("POST", "/api/runs", {{"scenario", "01_planar7_obstacles"}, {"mode", "batch"}, {"steps", 20}});
  ASSERT_EQ(batch.status, 200) << batch.body;
  const std::int64_t id = batch.json()["id"];
  const HttpResult resim = send("POST", "/api/runs/" + std::to_string(id) + "/replay", {{"mode", "resimulate"}});
  ASSERT_EQ(resim.status, 200) << resim.body;
  EXPECT_EQ(resim.json()["identical"], true);
  EXPECT_EQ(resim.json()["compared"], true);
  EXPECT_EQ(resim.json()["frames_compared"], 20);
  EXPECT_FALSE(resim.json().contains("reason"));
}

}  // namespace
}  // namespace rrlab::testing
