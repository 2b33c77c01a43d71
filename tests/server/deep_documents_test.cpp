// Regression cases for documents nested deep enough to overflow a recursive
// parser's stack: before the depth limits, 60,000 levels of JSON in a REST
// body (360-420 KB) and 140,000 nested elements of inline URDF (980 KB) each
// killed the server with SIGSEGV. Now every route answers 400 "too_deep" (a
// URDF: 422 at robot.urdf) naming the byte, the WebSocket replies with an
// error and stays open, and the server goes on answering (the command line:
// cli_test's DeepScenarioFilesAndSweepSpecs).
#include <algorithm>

#include "server_fixture.hpp"
#include "urdf_faults.hpp"

namespace rrlab::testing {
namespace {

using nlohmann::json;

// {"a": {"a": … 1 …}} with `levels` objects: 7 bytes a level (6 to open, 1 to close).
std::string nested_json(int levels) {
  std::string text;
  text.reserve(std::size_t(levels) * 6 + 1);
  for (int i = 0; i < levels; ++i) text += "{\"a\": ";
  text += "1";
  text.append(levels, '}');
  return text;
}

// A URDF whose <robot> holds `levels` - 1 nested <a> elements.
std::string nested_urdf(int levels) {
  std::string text = "<robot name=\"r\">";
  for (int i = 1; i < levels; ++i) text += "<a>";
  for (int i = 1; i < levels; ++i) text += "</a>";
  return text + "</robot>";
}

// The byte (1-based) of the bracket that opens level 65 of a body that wraps
// nested_json in `prefix`.
std::string too_deep_message(const std::string& body, const std::string& prefix) {
  const std::size_t levels_in_prefix = std::count(prefix.begin(), prefix.end(), '{');
  const std::size_t offset = prefix.size() + (64 - levels_in_prefix) * 6;
  EXPECT_EQ(body[offset], '{');
  return "JSON nested deeper than 64 levels at byte " + std::to_string(offset + 1);
}

class DeepDocuments : public ServerTest {
 protected:
  static void expect_alive(const std::string& after) {
    const HttpResult health = get("/api/health");
    EXPECT_EQ(health.status, 200) << "after " << after;
  }
};

TEST_F(DeepDocuments, EveryRestBodyAnswers400TooDeepAndTheServerLives) {
  const std::string prefix = R"({"scenario": )";
  const std::string body = prefix + nested_json(60000) + "}";  // 420 KB, under the 1 MiB body limit
  const std::string message = too_deep_message(body, prefix);
  for (const auto& [method, target] : std::vector<std::pair<std::string, std::string>>{
           {"POST", "/api/runs"}, {"POST", "/api/scenarios"}, {"POST", "/api/scenarios/validate"},
           {"POST", "/api/compare"}, {"POST", "/api/sweeps"}}) {
    const HttpResult r = http(port(), method, target, body);
    ASSERT_EQ(r.status, 400) << method << " " << target << ": " << r.body.substr(0, 300);
    EXPECT_EQ(error_of(r)["code"], "too_deep") << target;
    EXPECT_EQ(error_of(r)["message"], message) << target;
    expect_alive(target);
  }
  // at the limit the body is parsed, and refused for what it says
  const HttpResult shallow = http(port(), "POST", "/api/scenarios/validate", nested_json(64));
  EXPECT_EQ(shallow.status, 422) << shallow.body;
}

TEST_F(DeepDocuments, RunInputsAndTheWebSocketRefuseDeepMessages) {
  const std::int64_t id = start_live({{"scenario", small_scenario()}, {"paused", true}});
  const std::string base = "/api/runs/" + std::to_string(id);
  for (const char* route : {"/params", "/joystick", "/control", "/obstacles"}) {
    const HttpResult r = http(port(), route == std::string("/params") ? "PATCH" : "POST", base + route,
                              nested_json(30000));
    EXPECT_EQ(r.status, 400) << route << ": " << r.body.substr(0, 300);
    EXPECT_EQ(error_of(r)["code"], "too_deep") << route;
  }

  WsClient ws(port(), "/ws/runs/" + std::to_string(id));
  ASSERT_TRUE(ws.read_type("snapshot"));
  // 9,000 levels: 63 KB, under the 64 KiB message limit (a larger message closes the socket)
  ws.send(R"({"type": "input", "kind": "params", "payload": )" + nested_json(9000) + "}");
  const auto error = ws.read_type("error");
  ASSERT_TRUE(error) << "no error reply";
  EXPECT_EQ((*error)["error"]["code"], "too_deep") << *error;
  ASSERT_TRUE(ws.open());
  ws.send(R"({"type": "control", "action": "stop"})");
  EXPECT_TRUE(ws.read_type("ack")) << "no ack after the error";
  expect_alive("the WebSocket message");
}

TEST_F(DeepDocuments, DeepInlineUrdfIs422BeforeTheXmlParserRecurses) {
  for (const int levels : {140000, 20000}) {  // 980 KB: exit 139 before; 140 KB: 18.8 s before
    json scenario = urdf_faults::scenario({{"urdf", nested_urdf(levels)}});
    const HttpResult r = send("POST", "/api/scenarios/validate", scenario);
    ASSERT_EQ(r.status, 422) << levels << ": " << r.body.substr(0, 300);
    EXPECT_EQ(error_of(r)["path"], "robot.urdf") << r.body;
    EXPECT_NE(error_of(r)["message"].get<std::string>().find("XML nested deeper than 64 levels at byte"),
              std::string::npos)
        << r.body;
    expect_alive("a URDF of " + std::to_string(levels) + " levels");
  }
}

}  // namespace
}  // namespace rrlab::testing
