// One real `rrlab serve` per test suite, with helpers for the runs it serves.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <thread>

#include "client.hpp"
#include "server_process.hpp"
#include "support/eventually.hpp"

namespace rrlab::testing {

class ServerTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { server_ = std::make_unique<ServerProcess>(); }
  static void TearDownTestSuite() { server_.reset(); }

  static unsigned short port() { return server_->port(); }
  static HttpResult get(const std::string& target, const std::string& accept = "") {
    return http(port(), "GET", target, "", accept);
  }
  static HttpResult send(const std::string& method, const std::string& target, const nlohmann::json& body) {
    return http(port(), method, target, body.dump());
  }
  // Starts a live run and returns its id.
  static std::int64_t start_live(const nlohmann::json& body) {
    const HttpResult r = send("POST", "/api/runs", body);
    EXPECT_EQ(r.status, 201) << r.body;
    return r.json().at("id").get<std::int64_t>();
  }
  // Polls GET /api/runs/{id} until its status is one of the ended ones.
  static nlohmann::json wait_ended(std::int64_t id, int seconds = 60) {
    nlohmann::json run;
    const bool ended = rrlab::test::eventually(
        [&] {
          run = get("/api/runs/" + std::to_string(id)).json();
          const std::string status = run.at("status");
          return status == "completed" || status == "stopped" || status == "failed";
        },
        std::chrono::seconds(seconds), "run " + std::to_string(id) + " to end");
    return ended ? run : nlohmann::json{};
  }

  static inline std::unique_ptr<ServerProcess> server_;
};

// The error object of a 4xx answer.
inline nlohmann::json error_of(const HttpResult& r) { return r.json().at("error"); }

// A small planar scenario whose end-effector is joysticked (or follows a circle).
inline nlohmann::json small_scenario(const std::string& trajectory = "joystick", double duration = 600) {
  using nlohmann::json;
  json traj = trajectory == "joystick" ? json{{"type", "joystick"}}
                                       : json{{"type", "circle"}, {"center", {1.0, 0.5}}, {"radius", 0.2}};
  return {{"name", "small_" + trajectory},
          {"dt", 0.01},
          {"duration", duration},
          {"robot",
           {{"kind", "planar"},
            {"base", {0, 0}},
            {"links", json::array({{{"length", 0.5}, {"radius", 0.02}}, {{"length", 0.5}, {"radius", 0.02}},
                                   {{"length", 0.5}, {"radius", 0.02}}, {{"length", 0.5}, {"radius", 0.02}}})},
            {"q0", {0.6, -0.4, -0.4, -0.4}}}},
          {"obstacles", json::array({{{"id", "ball"}, {"shape", "sphere"}, {"center", {0.2, 1.0}}, {"radius", 0.1}}})},
          {"task", {{"space", "xy"}, {"trajectory", traj}}},
          {"method", {{"name", "gpm"}}}};
}

}  // namespace rrlab::testing
