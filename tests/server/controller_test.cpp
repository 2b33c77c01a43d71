// One controller per live run (app/controller.hpp): the first client to
// steer holds control, others get 409 "not_controller" until it releases,
// disconnects, or another client takes over (the holder is told). Unnamed
// REST requests (scripts) are no party to it.
#include <rrlab/server/app/controller.hpp>

#include <deque>
#include <map>

#include <rrlab/server/api/errors.hpp>

#include "server_fixture.hpp"

namespace rrlab::testing {
namespace {

using nlohmann::json;

class Control : public ServerTest {
 protected:
  static std::string ws(std::int64_t id, const std::string& client) {
    return "/ws/runs/" + std::to_string(id) + (client.empty() ? "" : "?client=" + client);
  }
  // The reply to a message: ack or error (frames skipped; control messages
  // kept for control_event: an ack comes once the input is stored, so the
  // news that the sender now holds control may come first).
  json reply(WsClient& c, const std::string& message) {
    c.send(message);
    for (int i = 0; i < 2000; ++i) {
      const auto m = c.read_json();
      if (!m) break;
      if ((*m)["type"] == "ack" || (*m)["type"] == "error") return *m;
      if ((*m)["type"] == "control") held_[&c].push_back(*m);
    }
    ADD_FAILURE() << "no reply to " << message;
    return {};
  }
  // The next control message with this event ("taken", "state"), others skipped.
  std::optional<json> control_event(WsClient& c, const std::string& event) {
    for (auto& held = held_[&c]; !held.empty();) {
      const json m = held.front();
      held.pop_front();
      if (m["event"] == event) return m;
    }
    for (int i = 0; i < 20; ++i) {
      const auto m = c.read_type("control");
      if (!m) return std::nullopt;
      if ((*m)["event"] == event) return m;
    }
    return std::nullopt;
  }
  std::map<WsClient*, std::deque<json>> held_;  // control messages read while waiting for a reply
  // Who holds control, as the next control state message tells `c`.
  std::string heard(WsClient& c) {
    const auto m = control_event(c, "state");
    return m ? (*m)["controller"].get<std::string>() : "(no control state message within 5 s)";
  }
  static HttpResult rest(const std::string& method, const std::string& target, const json& body,
                         const std::string& client) {
    std::map<std::string, std::string> headers;
    if (!client.empty()) headers["Rrlab-Client"] = client;
    return http(port(), method, target, body.dump(), "", headers);
  }
};

const std::string kJoystick = R"({"type":"input","kind":"joystick","payload":{"linear":[0.1,0]}})";

TEST_F(Control, SecondWebSocketClientWatchesUntilItTakesOver) {
  const std::int64_t id = start_live({{"scenario", small_scenario("joystick", 60)}, {"rate", 1}});
  WsClient alice(port(), ws(id, "alice")), bob(port(), ws(id, "bob"));
  ASSERT_TRUE(alice.read_type("snapshot"));
  ASSERT_TRUE(bob.read_type("snapshot"));
  EXPECT_EQ(reply(alice, kJoystick)["type"], "ack");  // the first to steer holds control
  const json refused = reply(bob, kJoystick);
  ASSERT_EQ(refused["type"], "error") << refused;
  EXPECT_EQ(refused["error"]["code"], "not_controller");
  EXPECT_NE(refused["error"]["message"].get<std::string>().find("\"take\""), std::string::npos);
  EXPECT_EQ(reply(bob, R"({"type":"control","action":"pause"})")["error"]["code"], "not_controller");
  // REST inputs of another named client are refused too; alice's own pass
  const std::string base = "/api/runs/" + std::to_string(id);
  const HttpResult bob_rest = rest("POST", base + "/control", {{"action", "pause"}}, "bob");
  EXPECT_EQ(bob_rest.status, 409);
  EXPECT_EQ(error_of(bob_rest)["code"], "not_controller");
  EXPECT_EQ(rest("POST", base + "/joystick", {{"linear", {0, 0}}}, "alice").status, 200);
  // an unnamed REST request (a script) is no party to control: it steers and holds nothing
  EXPECT_EQ(rest("POST", base + "/joystick", {{"linear", {0, 0}}}, "").status, 200);
  EXPECT_EQ(reply(bob, kJoystick)["error"]["code"], "not_controller");
  EXPECT_EQ(rest("POST", base + "/control", {{"action", "take"}}, "").status, 400);  // taking needs a name

  // bob takes over: alice is told and now watches
  const json taken = reply(bob, R"({"type":"control","action":"take"})");
  EXPECT_EQ(taken["type"], "ack");
  EXPECT_EQ(taken["status"]["controller"], "you");
  const auto told = control_event(alice, "taken");
  ASSERT_TRUE(told);
  EXPECT_EQ((*told)["event"], "taken");
  EXPECT_EQ((*told)["controller"], "other");
  EXPECT_EQ(reply(bob, kJoystick)["type"], "ack");
  EXPECT_EQ(reply(alice, kJoystick)["error"]["code"], "not_controller");

  // bob releases: the next to steer holds control
  EXPECT_EQ(reply(bob, R"({"type":"control","action":"release"})")["status"]["controller"], "none");
  EXPECT_EQ(reply(alice, kJoystick)["type"], "ack");
  EXPECT_EQ(reply(bob, kJoystick)["error"]["code"], "not_controller");
  EXPECT_EQ(reply(bob, R"({"type":"control","action":"take","x":1})")["error"]["code"], "invalid");
  EXPECT_EQ(rest("POST", base + "/control", {{"action", "stop"}}, "alice").status, 200);
  wait_ended(id);
}

TEST_F(Control, DisconnectReleasesControl) {
  const std::int64_t id = start_live({{"scenario", small_scenario("joystick", 60)}, {"rate", 1}});
  const std::string base = "/api/runs/" + std::to_string(id);
  {
    WsClient alice(port(), ws(id, "alice"));
    ASSERT_TRUE(alice.read_type("snapshot"));
    EXPECT_EQ(reply(alice, kJoystick)["type"], "ack");
    EXPECT_EQ(rest("POST", base + "/joystick", {{"linear", {0, 0}}}, "carol").status, 409);
  }
  // alice's socket closed: control is free again (the server sees the close a moment later)
  EXPECT_TRUE(rrlab::test::eventually(
      [&] { return rest("POST", base + "/joystick", {{"linear", {0, 0}}}, "carol").status == 200; },
      std::chrono::seconds(30), "carol's joystick accepted once alice's socket closed"));
  // carol holds control through REST alone until she releases it
  EXPECT_EQ(rest("POST", base + "/joystick", {{"linear", {0, 0}}}, "dave").status, 409);
  EXPECT_EQ(rest("POST", base + "/control", {{"action", "release"}}, "carol").json()["controller"], "none");
  // a WebSocket without a name is a client of its own
  WsClient first(port(), ws(id, "")), second(port(), ws(id, ""));
  ASSERT_TRUE(first.read_type("snapshot"));
  ASSERT_TRUE(second.read_type("snapshot"));
  EXPECT_EQ(reply(first, kJoystick)["type"], "ack");
  EXPECT_EQ(reply(second, kJoystick)["error"]["code"], "not_controller");
  EXPECT_EQ(reply(second, R"({"type":"control","action":"take"})")["status"]["controller"], "you");
  ASSERT_TRUE(control_event(first, "taken"));
  EXPECT_EQ(reply(first, kJoystick)["error"]["code"], "not_controller");
  EXPECT_EQ(send("POST", base + "/control", {{"action", "stop"}}).status, 200);
  wait_ended(id);
}

TEST_F(Control, EveryClientHearsWhoHoldsControl) {
  const std::int64_t id = start_live({{"scenario", small_scenario("joystick", 60)}, {"rate", 1}});
  auto alice = std::make_unique<WsClient>(port(), ws(id, "alice"));
  WsClient bob(port(), ws(id, "bob"));
  // on connecting: nobody holds it
  const auto alice_first = control_event(*alice, "state");
  const auto bob_first = control_event(bob, "state");
  ASSERT_TRUE(alice_first && bob_first);
  EXPECT_EQ((*alice_first)["controller"], "none");
  EXPECT_EQ((*bob_first)["controller"], "none");
  // alice steers: each hears it from its side, before anyone tries to steer
  EXPECT_EQ(reply(*alice, kJoystick)["type"], "ack");
  EXPECT_EQ(heard(bob), "other");
  EXPECT_EQ(heard(*alice), "you");
  // alice lets go: bob hears that nobody holds it
  EXPECT_EQ(reply(*alice, R"({"type":"control","action":"release"})")["status"]["controller"], "none");
  EXPECT_EQ(heard(bob), "none");
  // alice steers again and leaves: bob hears it is free
  EXPECT_EQ(reply(*alice, kJoystick)["type"], "ack");
  EXPECT_EQ(heard(bob), "other");
  alice.reset();
  EXPECT_EQ(heard(bob), "none");
  EXPECT_EQ(send("POST", "/api/runs/" + std::to_string(id) + "/control", {{"action", "stop"}}).status, 200);
  wait_ended(id);
}

TEST_F(Control, ARefusedMessageTakesNoControl) {
  const std::int64_t id = start_live({{"scenario", small_scenario()}, {"paused", true}});
  WsClient alice(port(), ws(id, "alice")), bob(port(), ws(id, "bob"));
  ASSERT_TRUE(alice.read_type("snapshot"));
  ASSERT_TRUE(bob.read_type("snapshot"));
  EXPECT_EQ(reply(alice, R"({"type": "bogus"})")["error"]["code"], "invalid");
  EXPECT_EQ(reply(bob, kJoystick)["type"], "ack") << "alice's refused message took control";
  EXPECT_EQ(reply(alice, kJoystick)["error"]["code"], "not_controller");
  EXPECT_EQ(send("POST", "/api/runs/" + std::to_string(id) + "/control", {{"action", "stop"}}).status, 200);
}

TEST(ControllerUnit, ClaimTakeRelease) {
  server::Controller c;
  std::vector<json> told_a;
  const auto a1 = c.attach("a", [&](const json& m) { told_a.push_back(m); });
  const auto nothing = [] {};
  c.steer("", nothing);  // unnamed: allowed, holds nothing
  EXPECT_EQ(c.state_json("a")["controller"], "none");
  c.steer("a", nothing);
  EXPECT_EQ(c.state_json("a")["controller"], "you");
  EXPECT_EQ(c.state_json("b")["controller"], "other");
  EXPECT_THROW(c.steer("b", nothing), server::DomainError);
  EXPECT_NO_THROW(c.steer("", nothing));  // still no party to it
  EXPECT_EQ(c.take("b")["controller"], "you");
  // a: the state when attached (none), when it claimed (you), taken, the state after (other)
  ASSERT_EQ(told_a.size(), 4u);
  EXPECT_EQ(told_a[0]["controller"], "none");
  EXPECT_EQ(told_a[1]["controller"], "you");
  EXPECT_EQ(told_a[2]["event"], "taken");
  EXPECT_EQ(told_a[3]["event"], "state");
  EXPECT_EQ(told_a[3]["controller"], "other");
  EXPECT_EQ(c.take("b")["controller"], "you");  // taking what one holds tells nobody
  EXPECT_EQ(told_a.size(), 4u);
  c.release("a");  // not the holder: nothing
  EXPECT_EQ(c.state_json("b")["controller"], "you");
  c.detach(a1);
  const auto b1 = c.attach("b", nullptr), b2 = c.attach("b", nullptr);  // no notify: nothing sent
  c.detach(b1);  // b still has a connection
  EXPECT_EQ(c.state_json("b")["controller"], "you");
  c.detach(b2);
  EXPECT_EQ(c.state_json("b")["controller"], "none");
  EXPECT_THROW(c.take(""), server::DomainError);
  EXPECT_EQ(server::valid_client_name("tab-0a1b"), "tab-0a1b");
  EXPECT_EQ(server::valid_client_name("a b"), "");
  EXPECT_EQ(server::valid_client_name(std::string(65, 'a')), "");
}

// A refused input takes nothing: before, {"type": "bogus"} from a watcher
// took control although it was refused as invalid.
TEST(ControllerUnit, ARefusedInputTakesNothing) {
  server::Controller c;
  int told = 0;
  c.attach("a", [&](const json&) { ++told; });
  EXPECT_EQ(told, 1);  // the state when attached
  EXPECT_THROW(c.steer("a", [] { throw server::DomainError(server::Problem::invalid, "invalid", "bogus", "type"); }), server::DomainError);
  EXPECT_EQ(c.state_json("b")["controller"], "none");
  EXPECT_EQ(told, 1);  // nobody was told of a hold that did not last
  EXPECT_EQ(c.steer("a", [] { return 7; }), 7);
  EXPECT_EQ(c.state_json("b")["controller"], "other");
  EXPECT_EQ(told, 2);
  // the holder's refused input keeps the control it already held
  EXPECT_THROW(c.steer("a", [] { throw server::DomainError(server::Problem::conflict, "wrong_state", "x"); }), server::DomainError);
  EXPECT_EQ(c.state_json("a")["controller"], "you");
}

// A holder with no WebSocket (REST only) loses control after the lapse
// without a request; one with a WebSocket keeps it.
TEST(ControllerUnit, RestOnlyControlLapses) {
  auto now = server::Controller::Clock::time_point{};
  server::Controller c([&] { return now; }, std::chrono::seconds(60));
  const auto nothing = [] {};
  c.steer("script", nothing);
  now += std::chrono::seconds(59);
  EXPECT_THROW(c.steer("tab", nothing), server::DomainError);
  c.steer("script", nothing);  // a request keeps it
  now += std::chrono::seconds(60);
  EXPECT_EQ(c.state_json("tab")["controller"], "other");
  now += std::chrono::seconds(1);
  EXPECT_EQ(c.state_json("tab")["controller"], "none");
  std::vector<json> told;
  const auto socket = c.attach("tab", [&](const json& m) { told.push_back(m); });
  c.steer("tab", nothing);
  EXPECT_EQ(told.back()["controller"], "you");
  now += std::chrono::hours(1);  // with a WebSocket open, no lapse
  EXPECT_THROW(c.steer("script", nothing), server::DomainError);
  c.detach(socket);
  EXPECT_NO_THROW(c.steer("script", nothing));
}

}  // namespace
}  // namespace rrlab::testing
