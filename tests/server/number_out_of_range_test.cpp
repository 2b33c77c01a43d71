// A number beyond double's range (1e309) in JSON from a client is malformed
// JSON: 400 "malformed_json" naming the byte over REST, an error reply over the
// WebSocket (which stays open); never a 500 or the parser's exception text.
#include "server_fixture.hpp"

namespace rrlab::testing {
namespace {

using nlohmann::json;

class NumberOutOfRange : public ServerTest {};

void expect_plain_malformed_json(const HttpResult& r, const std::string& what) {
  EXPECT_EQ(r.status, 400) << what << ": " << r.body;
  const json error = error_of(r);
  EXPECT_EQ(error["code"], "malformed_json") << what;
  const std::string message = error["message"];
  EXPECT_EQ(message.find("json.exception"), std::string::npos) << what << ": " << message;
  EXPECT_EQ(message.find("[json"), std::string::npos) << what << ": " << message;
}

TEST_F(NumberOutOfRange, RestBodiesAnswer400NamingTheByte) {
  const std::string overflow = R"({"scenario": "01_planar7_obstacles", "rate": 1e309})";
  const HttpResult run = http(port(), "POST", "/api/runs", overflow);
  expect_plain_malformed_json(run, "POST /api/runs");
  EXPECT_EQ(error_of(run)["message"], "number out of range at byte " + std::to_string(overflow.find("1e309") + 5));

  for (const auto& [method, target] : std::vector<std::pair<std::string, std::string>>{
           {"POST", "/api/scenarios"}, {"POST", "/api/scenarios/validate"}, {"POST", "/api/compare"},
           {"POST", "/api/sweeps"}})
    expect_plain_malformed_json(http(port(), method, target, R"({"x": [1, -1e309]})"), method + " " + target);
}

TEST_F(NumberOutOfRange, RunInputsAnswer400) {
  const std::int64_t id = start_live({{"scenario", small_scenario()}, {"paused", true}});
  const std::string base = "/api/runs/" + std::to_string(id);
  expect_plain_malformed_json(http(port(), "PATCH", base + "/params", R"({"gain": 1e309})"), "params");
  expect_plain_malformed_json(http(port(), "POST", base + "/joystick", R"({"linear": [1e309, 0]})"), "joystick");
  expect_plain_malformed_json(http(port(), "POST", base + "/control", R"({"action": "start", "rate": 1e309})"),
                              "control");
  EXPECT_EQ(send("POST", base + "/control", {{"action", "stop"}}).status, 200);
}

TEST_F(NumberOutOfRange, SyntaxErrorsGetAPlainMessageToo) {
  const HttpResult r = http(port(), "POST", "/api/scenarios/validate", "{\"robot\":");
  expect_plain_malformed_json(r, "truncated");
  EXPECT_NE(error_of(r)["message"].get<std::string>().find("at byte 10"), std::string::npos) << r.body;
}

TEST_F(NumberOutOfRange, WebSocketRepliesWithAnErrorAndStaysOpen) {
  const std::int64_t id = start_live({{"scenario", small_scenario()}, {"paused", true}});
  WsClient ws(port(), "/ws/runs/" + std::to_string(id));
  ASSERT_TRUE(ws.read_type("snapshot"));
  ws.send(R"({"type": "input", "kind": "params", "payload": {"gain": 1e309}})");
  const auto error = ws.read_type("error");
  ASSERT_TRUE(error) << "no error reply";
  EXPECT_EQ((*error)["error"]["code"], "malformed_json");
  EXPECT_EQ((*error)["error"]["message"].get<std::string>().rfind("number out of range at byte ", 0), 0u) << *error;

  // the socket is still open and still answers
  ASSERT_TRUE(ws.open());
  ws.send(R"({"type": "control", "action": "stop"})");
  const auto ack = ws.read_type("ack");
  ASSERT_TRUE(ack) << "no ack after the error";
  EXPECT_TRUE(ws.open());
}

}  // namespace
}  // namespace rrlab::testing
