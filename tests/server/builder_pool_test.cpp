// Scenario building runs on the builder pool, never on the I/O threads:
// before, two requests whose URDF took 22 s to check made /api/health wait
// 37 s. Here every build is held for a while (a test-only delay); health
// answers, from the two I/O threads, while four builds are under way.
#include <atomic>
#include <thread>

#include "server_fixture.hpp"

namespace rrlab::testing {
namespace {

using nlohmann::json;

TEST(BuilderPool, HealthAnswersWhileScenariosAreBuilt) {
  ServerProcess server("", {"--threads", "2", "--test-build-delay-ms", "4000"});
  const std::string scenario = json{{"scenario", small_scenario("circle", 1.0)}}["scenario"].dump();
  std::atomic<int> validated{0};
  std::vector<std::thread> builds;
  for (int i = 0; i < 4; ++i)
    builds.emplace_back([&] {
      if (http(server.port(), "POST", "/api/scenarios/validate", scenario).status == 200) ++validated;
    });
  // until the server says all four are being built (60 s at most)
  json health;
  ASSERT_TRUE(rrlab::test::eventually(
      [&] { return (health = http(server.port(), "GET", "/api/health").json())["building"] == 4; },
      std::chrono::seconds(60), "the four builds under way at once"))
      << health.dump();
  // answered during the builds: health says they are still under way
  int answered_while_building = 0;
  for (int i = 0; i < 5; ++i) {
    const HttpResult r = http(server.port(), "GET", "/api/health");
    EXPECT_EQ(r.status, 200);
    if (r.json()["building"].get<int>() > 0) ++answered_while_building;
  }
  EXPECT_GE(answered_while_building, 1) << "health waited for the builds";
  for (auto& b : builds) b.join();
  EXPECT_EQ(validated, 4);
  EXPECT_EQ(http(server.port(), "GET", "/api/health").json()["building"], 0);
}

}  // namespace
}  // namespace rrlab::testing
