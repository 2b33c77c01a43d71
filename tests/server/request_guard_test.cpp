// Who may talk to the server (net/request_guard.hpp): a real server refuses
// foreign Hosts (DNS rebinding), changes and WebSockets from foreign Origins,
// a second Host or Origin, and API bodies that are not JSON; --allow-host and
// --allow-origin widen that. Then the decision table itself.
#include <rrlab/server/net/request_guard.hpp>

#include "raw_connection.hpp"
#include "server_fixture.hpp"

namespace rrlab::testing {
namespace {

using nlohmann::json;
using Headers = std::map<std::string, std::string>;

class RequestGuard : public ServerTest {
 protected:
  static std::string own_origin() { return "http://127.0.0.1:" + std::to_string(port()); }
  static std::size_t run_count() { return get("/api/runs").json().size(); }
  static HttpResult post(const std::string& target, const json& body, const Headers& headers) {
    return http(port(), "POST", target, body.dump(), "", headers);
  }
};

TEST_F(RequestGuard, ForeignOriginMayNotChangeAnythingNorStartRuns) {
  const std::size_t before = run_count();
  const json body = {{"scenario", small_scenario("joystick", 60)}, {"rate", 1}};
  for (const std::string& origin : std::vector<std::string>{"http://evil.example", "http://127.0.0.1:1",
                                                            "https://127.0.0.1:" + std::to_string(port()), "null"}) {
    const HttpResult r = post("/api/runs", body, {{"Origin", origin}});
    EXPECT_EQ(r.status, 403) << origin << ": " << r.body;
    EXPECT_EQ(error_of(r)["code"], "forbidden_origin");
    EXPECT_NE(error_of(r)["message"].get<std::string>().find("--allow-origin"), std::string::npos);
    EXPECT_EQ(r.headers.count("access-control-allow-origin"), 0u);
  }
  EXPECT_EQ(http(port(), "DELETE", "/api/runs/1", "", "", {{"Origin", "http://evil.example"}}).status, 403);
  EXPECT_EQ(http(port(), "PATCH", "/api/runs/1/params", "{}", "", {{"Origin", "http://evil.example"}}).status, 403);
  EXPECT_EQ(run_count(), before);
  // reading is not a change: a foreign page cannot read the answer without CORS anyway
  EXPECT_EQ(http(port(), "GET", "/api/health", "", "", {{"Origin", "http://evil.example"}}).status, 200);
}

TEST_F(RequestGuard, SameOriginAndOriginlessJsonPostsPass) {
  const std::string scenario = get("/api/scenarios/01_planar7_obstacles").body;
  for (const std::string& origin :
       std::vector<std::string>{own_origin(), "http://localhost:" + std::to_string(port())}) {
    const HttpResult r = http(port(), "POST", "/api/scenarios/validate", scenario, "",
                              {{"Origin", origin}, {"Content-Type", "application/json; charset=utf-8"}});
    EXPECT_EQ(r.status, 200) << origin << ": " << r.body;
  }
  const HttpResult started =
      post("/api/runs", {{"scenario", small_scenario("joystick", 60)}, {"rate", 1}}, {{"Origin", own_origin()}});
  ASSERT_EQ(started.status, 201) << started.body;
  const std::string id = std::to_string(started.json().at("id").get<std::int64_t>());
  EXPECT_EQ(post("/api/runs/" + id + "/control", {{"action", "stop"}}, {}).status, 200);  // no Origin: curl
  wait_ended(std::stoll(id));
}

TEST_F(RequestGuard, ForeignHostIsMisdirected) {
  const std::size_t before = run_count();
  const std::string p = std::string(1, ':').append(std::to_string(port()));
  for (const std::string& host :
       std::vector<std::string>{"evil.example" + p, "evil.example", "127.0.0.1", "localhost:1", "127.0.0.1:80x"}) {
    const HttpResult r = http(port(), "GET", "/api/health", "", "", {{"Host", host}});
    EXPECT_EQ(r.status, 421) << host << ": " << r.body;
    EXPECT_EQ(error_of(r)["code"], "misdirected");
    EXPECT_NE(error_of(r)["message"].get<std::string>().find("--allow-host"), std::string::npos);
  }
  // a rebound name with no Origin (same-origin GET/HEAD send none) is refused too
  EXPECT_EQ(post("/api/runs", {{"scenario", small_scenario("joystick", 60)}}, {{"Host", "evil.example" + p}}).status,
            421);
  EXPECT_EQ(get("/index.html").status, 200);
  EXPECT_EQ(http(port(), "GET", "/index.html", "", "", {{"Host", "evil.example" + p}}).status, 421);
  EXPECT_EQ(run_count(), before);
  for (const std::string& host :
       std::vector<std::string>{"localhost" + p, "LOCALHOST" + p, "[::1]" + p, "127.0.0.1" + p})
    EXPECT_EQ(http(port(), "GET", "/api/health", "", "", {{"Host", host}}).status, 200) << host;
  // no Host (HTTP/1.0): allowed on a loopback bind
  EXPECT_EQ(http(port(), "GET", "/api/health", "", "", {{"Host", ""}}).status, 200);
}

TEST_F(RequestGuard, ApiBodiesMustBeJson) {
  const std::string scenario = get("/api/scenarios/01_planar7_obstacles").body;
  for (const std::string& type : std::vector<std::string>{"text/plain", "application/x-www-form-urlencoded",
                                                          "multipart/form-data; boundary=x", "application/jsonx", ""}) {
    const HttpResult r = http(port(), "POST", "/api/scenarios/validate", scenario, "", {{"Content-Type", type}});
    EXPECT_EQ(r.status, 415) << "'" << type << "': " << r.body;
    EXPECT_EQ(error_of(r)["code"], "unsupported_media_type");
    EXPECT_NE(error_of(r)["message"].get<std::string>().find("Content-Type"), std::string::npos);
  }
  const std::size_t before = run_count();
  EXPECT_EQ(http(port(), "POST", "/api/runs", R"({"scenario": "01_planar7_obstacles", "mode": "batch"})", "",
                 {{"Content-Type", "text/plain"}})
                .status,
            415);
  EXPECT_EQ(run_count(), before);
  for (const std::string& type : std::vector<std::string>{"application/json", "Application/JSON ; charset=UTF-8"})
    EXPECT_EQ(http(port(), "POST", "/api/scenarios/validate", scenario, "", {{"Content-Type", type}}).status, 200)
        << type;
  // no body: the Content-Type does not matter (the route answers as before)
  EXPECT_EQ(http(port(), "POST", "/api/runs", "", "", {{"Content-Type", "text/plain"}}).status, 400);
  EXPECT_EQ(http(port(), "DELETE", "/api/runs/999999", "", "", {{"Content-Type", "text/plain"}}).status, 404);
}

TEST_F(RequestGuard, WebSocketUpgradeFromForeignOriginIsRefused) {
  const std::int64_t id = start_live({{"scenario", small_scenario("joystick", 60)}, {"rate", 1}});
  const std::string ws = "/ws/runs/" + std::to_string(id);
  const HttpResult foreign = ws_upgrade(port(), ws, {{"Origin", "http://evil.example"}});
  EXPECT_EQ(foreign.status, 403) << foreign.body;
  EXPECT_EQ(json::parse(foreign.body)["error"]["code"], "forbidden_origin");
  EXPECT_EQ(ws_upgrade(port(), ws, {{"Origin", own_origin()}}).status, 101);
  EXPECT_EQ(ws_upgrade(port(), ws).status, 101);  // no Origin: not a browser
  EXPECT_EQ(ws_upgrade(port(), ws, {{"Host", "evil.example:" + std::to_string(port())}}).status, 421);
  WsClient client(port(), ws, {{"Origin", own_origin()}});
  const auto snapshot = client.read_type("snapshot");
  ASSERT_TRUE(snapshot);
  EXPECT_EQ(send("POST", "/api/runs/" + std::to_string(id) + "/control", {{"action", "stop"}}).status, 200);
  wait_ended(id);
}

// Sends raw `request` (a Host or Origin twice: no HTTP client would) and
// returns the status and the JSON body of the answer.
std::pair<int, json> send_raw(unsigned short port, const std::string& request) {
  RawConnection connection(port);
  EXPECT_TRUE(connection.write(request));
  const std::string answer = connection.read_until("\r\n\r\n");
  const auto header_end = answer.find("\r\n\r\n");
  if (status_of(answer) == 101 || header_end == std::string::npos) return {status_of(answer), json()};
  const std::string full = connection.read_until("}}");  // the error object's end
  return {status_of(full), json::parse(full.substr(header_end + 4), nullptr, false)};
}

TEST_F(RequestGuard, TwoHostsOrTwoOriginsAreRefused) {
  const std::string own_host = "Host: 127.0.0.1:" + std::to_string(port()) + "\r\n";
  const std::string own = "Origin: " + own_origin() + "\r\n", foreign = "Origin: http://evil.example\r\n";
  const auto expect_refused = [](const std::pair<int, json>& answer, const std::string& header,
                                 const std::string& what) {
    EXPECT_EQ(answer.first, 400) << what;
    const json error = answer.second.is_object() ? answer.second.value("error", json::object()) : json::object();
    EXPECT_EQ(error.value("code", ""), "duplicate_header") << what << ": " << answer.second;
    EXPECT_EQ(error.value("path", ""), header) << what;
    EXPECT_NE(error.value("message", "").find(header), std::string::npos) << what << ": " << answer.second;
  };
  // plain HTTP: the own Host first or second, or twice the same
  for (const std::string& hosts :
       {own_host + "Host: evil.example\r\n", "Host: evil.example\r\n" + own_host, own_host + own_host})
    expect_refused(send_raw(port(), "GET /api/health HTTP/1.1\r\n" + hosts + "Connection: close\r\n\r\n"), "Host",
                   "GET with " + hosts);
  const std::string post = "POST /api/scenarios/validate HTTP/1.1\r\n" + own_host +
                           "Content-Type: application/json\r\nContent-Length: 2\r\nConnection: close\r\n";
  expect_refused(send_raw(port(), post + own + foreign + "\r\n{}"), "Origin", "POST, own Origin then foreign");
  expect_refused(send_raw(port(), post + own + own + "\r\n{}"), "Origin", "POST, own Origin twice");
  EXPECT_EQ(send_raw(port(), post + own + "\r\n{}").first, 422);  // one Origin: the body is judged

  // WebSocket upgrades
  const std::int64_t id = start_live({{"scenario", small_scenario("joystick", 60)}, {"rate", 1}});
  const std::string ws = "/ws/runs/" + std::to_string(id);
  expect_refused(send_raw(port(), websocket_upgrade_request(port(), ws, own + foreign)), "Origin",
                 "upgrade, 2 Origins");
  expect_refused(send_raw(port(), websocket_upgrade_request(port(), ws, "Host: evil.example\r\n")), "Host",
                 "upgrade, 2 Hosts");
  EXPECT_EQ(send_raw(port(), websocket_upgrade_request(port(), ws, own)).first, 101);
  EXPECT_EQ(send("POST", "/api/runs/" + std::to_string(id) + "/control", {{"action", "stop"}}).status, 200);
  wait_ended(id);
}

TEST(RequestGuardOptions, AllowOriginAndAllowHostWidenTheRules) {
  ServerProcess server("", {"--allow-origin", "http://lab.example:3000", "--allow-origin", "https://lab.example/",
                            "--allow-host", "rrlab.example", "--allow-host", "10.0.0.7:8443"});
  const unsigned short port = server.port();
  const std::string scenario = http(port, "GET", "/api/scenarios/01_planar7_obstacles").body;
  for (const std::string& origin :
       std::vector<std::string>{"http://lab.example:3000", "https://lab.example", "HTTPS://LAB.EXAMPLE:443"}) {
    HttpResult r = http(port, "POST", "/api/scenarios/validate", scenario, "", {{"Origin", origin}});
    EXPECT_EQ(r.status, 200) << origin << ": " << r.body;
    EXPECT_EQ(r.headers["access-control-allow-origin"], origin);
    EXPECT_EQ(r.headers["vary"], "Origin");
  }
  // the preflight a browser sends before a JSON POST
  HttpResult preflight = http(port, "OPTIONS", "/api/runs", "", "",
                              {{"Origin", "http://lab.example:3000"}, {"Access-Control-Request-Method", "POST"}});
  EXPECT_EQ(preflight.status, 204);
  EXPECT_EQ(preflight.headers["access-control-allow-origin"], "http://lab.example:3000");
  EXPECT_NE(preflight.headers["access-control-allow-methods"].find("POST"), std::string::npos);
  EXPECT_EQ(preflight.headers["access-control-allow-headers"], "Content-Type");
  // other origins still get neither CORS nor changes
  const HttpResult other = http(port, "OPTIONS", "/api/runs", "", "", {{"Origin", "http://lab.example:3001"}});
  EXPECT_NE(other.status, 204);
  EXPECT_EQ(other.headers.count("access-control-allow-origin"), 0u);
  EXPECT_EQ(http(port, "POST", "/api/scenarios/validate", scenario, "", {{"Origin", "http://lab.example:3001"}}).status,
            403);
  // a 415 for an allowed origin carries CORS, so that its page can read why
  HttpResult plain = http(port, "POST", "/api/scenarios/validate", scenario, "",
                          {{"Origin", "http://lab.example:3000"}, {"Content-Type", "text/plain"}});
  EXPECT_EQ(plain.status, 415);
  EXPECT_EQ(plain.headers["access-control-allow-origin"], "http://lab.example:3000");

  // --allow-host: any port for a bare name, that port for NAME:PORT; its http origin is this server's
  for (const std::string& host : std::vector<std::string>{"rrlab.example", "rrlab.example:443",
                                                          "RRLAB.example:" + std::to_string(port), "10.0.0.7:8443"})
    EXPECT_EQ(http(port, "GET", "/api/health", "", "", {{"Host", host}}).status, 200) << host;
  for (const std::string& host :
       std::vector<std::string>{"10.0.0.7", "10.0.0.7:" + std::to_string(port), "rrlab.example.evil"})
    EXPECT_EQ(http(port, "GET", "/api/health", "", "", {{"Host", host}}).status, 421) << host;
  EXPECT_EQ(http(port, "POST", "/api/scenarios/validate", scenario, "",
                 {{"Host", "rrlab.example"}, {"Origin", "http://rrlab.example"}})
                .status,
            200);
  // a page of another server on that host (another port) is not this server's origin
  EXPECT_EQ(http(port, "POST", "/api/scenarios/validate", scenario, "",
                 {{"Host", "rrlab.example:" + std::to_string(port)}, {"Origin", "http://rrlab.example:3000"}})
                .status,
            403);

  // WebSockets from an allowed origin
  const HttpResult run = http(port, "POST", "/api/runs", json{{"scenario", small_scenario("joystick", 60)}}.dump());
  ASSERT_EQ(run.status, 201) << run.body;
  const std::string id = std::to_string(run.json().at("id").get<std::int64_t>());
  EXPECT_EQ(ws_upgrade(port, "/ws/runs/" + id, {{"Origin", "http://lab.example:3000"}}).status, 101);
  EXPECT_EQ(ws_upgrade(port, "/ws/runs/" + id, {{"Origin", "http://lab.example:3001"}}).status, 403);
  EXPECT_EQ(http_json(port, "POST", "/api/runs/" + id + "/control", {{"action", "stop"}}).status, 200);
}

TEST(RequestGuardOptions, MalformedAllowOriginIsBadInput) {
  const CommandResult r = run_rrlab({"serve", "--port", "0", "--allow-origin", "lab.example"});
  EXPECT_EQ(r.exit_code, 2);
}

// The decision table, without a server.
using server::AccessConfig;
using server::AccessRequest;
using server::check_access;

int status_of(const AccessConfig& config, const std::string& method, const std::string& host, const std::string& origin,
              const std::string& content_type = "", bool body = false, bool upgrade = false,
              const std::string& target = "/api/runs") {
  return check_access(config, AccessRequest{method, target, host, origin, content_type, body, upgrade}).status;
}

TEST(RequestGuardTable, Decisions) {
  const AccessConfig loopback{"127.0.0.1", 8080, {}, {}};
  EXPECT_EQ(status_of(loopback, "GET", "127.0.0.1:8080", ""), 0);
  EXPECT_EQ(status_of(loopback, "GET", "localhost:8080", ""), 0);
  EXPECT_EQ(status_of(loopback, "GET", "[::1]:8080", ""), 0);
  EXPECT_EQ(status_of(loopback, "GET", "", ""), 0);
  EXPECT_EQ(status_of(loopback, "GET", "evil.example:8080", ""), 421);
  EXPECT_EQ(status_of(loopback, "GET", "localhost", ""), 421);  // port 80
  EXPECT_EQ(status_of(loopback, "GET", "::1:8080", ""), 421);   // IPv6 needs brackets
  EXPECT_EQ(status_of(loopback, "GET", "localhost:99999", ""), 421);
  EXPECT_EQ(status_of(loopback, "POST", "localhost:8080", "http://localhost:8080", "application/json", true), 0);
  EXPECT_EQ(status_of(loopback, "POST", "localhost:8080", "http://127.0.0.1:8080/", "application/json", true), 0);
  EXPECT_EQ(status_of(loopback, "POST", "localhost:8080", "http://evil.example", "application/json", true), 403);
  EXPECT_EQ(status_of(loopback, "PUT", "localhost:8080", "file://", "application/json", true), 403);
  EXPECT_EQ(status_of(loopback, "FOO", "localhost:8080", "http://evil.example"), 403);  // any unsafe method
  EXPECT_EQ(status_of(loopback, "GET", "localhost:8080", "http://evil.example", "", false, true, "/ws/runs/1"), 403);
  EXPECT_EQ(status_of(loopback, "GET", "localhost:8080", "http://evil.example"), 0);
  EXPECT_EQ(status_of(loopback, "OPTIONS", "localhost:8080", "http://evil.example"), 0);  // no CORS: the route's 405
  EXPECT_EQ(status_of(loopback, "POST", "localhost:8080", "", "text/plain", true), 415);
  EXPECT_EQ(status_of(loopback, "POST", "localhost:8080", "", "text/plain", false), 0);
  EXPECT_EQ(status_of(loopback, "POST", "localhost:8080", "", "text/plain", true, false, "/index.html"), 0);
  EXPECT_EQ(
      status_of(loopback, "POST", "localhost:8080", "", "application/json;charset=utf-8", true, false, "/api?x=1"), 0);

  const AccessConfig v6{"::1", 9000, {}, {}};
  EXPECT_EQ(status_of(v6, "GET", "[::1]:9000", ""), 0);
  EXPECT_EQ(status_of(v6, "GET", "", ""), 0);
  EXPECT_EQ(status_of(v6, "POST", "[::1]:9000", "http://[::1]:9000", "application/json", true), 0);

  const AccessConfig wildcard{"0.0.0.0", 8080, {"lab-pc", "rrlab.example.org:443"}, {"https://rrlab.example.org"}};
  EXPECT_EQ(status_of(wildcard, "GET", "", ""), 400);  // no Host on a non-loopback bind
  EXPECT_EQ(status_of(wildcard, "GET", "192.168.1.5:8080", ""), 421);
  EXPECT_EQ(status_of(wildcard, "GET", "lab-pc:8080", ""), 0);
  EXPECT_EQ(status_of(wildcard, "GET", "rrlab.example.org", ""), 421);  // port 80, not 443
  EXPECT_EQ(status_of(wildcard, "GET", "rrlab.example.org:443", ""), 0);
  EXPECT_EQ(status_of(wildcard, "POST", "rrlab.example.org:443", "https://rrlab.example.org", "application/json", true),
            0);
  EXPECT_EQ(status_of(wildcard, "POST", "lab-pc:8080", "http://lab-pc:8080", "application/json", true), 0);
  // another server on the allowed host is not this one's origin (it was: any port of a bare --allow-host)
  EXPECT_EQ(status_of(wildcard, "POST", "lab-pc:8080", "http://lab-pc:3000", "application/json", true), 403);
  EXPECT_EQ(status_of(wildcard, "POST", "lab-pc:8080", "http://lab-pc", "application/json", true), 403);
  EXPECT_EQ(status_of(wildcard, "POST", "lab-pc", "http://lab-pc", "application/json", true), 0);  // behind a proxy on 80
  const auto preflight =
      check_access(wildcard, {"OPTIONS", "/api/runs", "lab-pc:8080", "https://rrlab.example.org", "", false, false});
  AccessRequest twice{"GET", "/api/health", "localhost:8080", "http://localhost:8080", "", false, false, "", "", 2, 1};
  EXPECT_EQ(check_access(loopback, twice).status, 400);
  EXPECT_EQ(check_access(loopback, twice).path, "Host");
  twice.host_fields = 1;
  twice.origin_fields = 2;
  EXPECT_EQ(check_access(loopback, twice).code, "duplicate_header");
  EXPECT_EQ(check_access(loopback, twice).path, "Origin");
  twice.origin_fields = 1;
  EXPECT_EQ(check_access(loopback, twice).status, 0);
  EXPECT_EQ(preflight.status, 204);
  EXPECT_FALSE(preflight.headers.empty());

  EXPECT_EQ(server::normalize_origin("HTTP://Lab.Example:80/"), "http://lab.example");
  EXPECT_EQ(server::normalize_origin("https://lab.example:8443"), "https://lab.example:8443");
  EXPECT_EQ(server::normalize_origin("lab.example"), "");
  EXPECT_EQ(server::normalize_origin("ftp://lab.example"), "");
}

}  // namespace
}  // namespace rrlab::testing
