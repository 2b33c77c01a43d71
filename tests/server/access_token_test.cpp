// --token (net/request_guard.hpp rule 3): mutating routes, reads and
// WebSocket upgrades need Authorization: Bearer TOKEN (a WebSocket may pass
// token=TOKEN in its query) unless --public-read opens reads; /api/health and
// static files stay open; 401 with a JSON error otherwise. And serve's refusal
// to bind a non-loopback address without a token.
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>

#include <rrlab/server/net/request_guard.hpp>

#include "server_fixture.hpp"

namespace rrlab::testing {
namespace {

using nlohmann::json;
using Headers = std::map<std::string, std::string>;

const std::string kToken = "s3cret-Token_0123456789";
const Headers kAuth = {{"Authorization", "Bearer " + kToken}};

class TokenServer : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    server_ = std::make_unique<ServerProcess>("", std::vector<std::string>{"--token", kToken});
  }
  static void TearDownTestSuite() { server_.reset(); }
  static unsigned short port() { return server_->port(); }
  static HttpResult request(const std::string& method, const std::string& target, const Headers& headers,
                            const std::string& body = "") {
    return http(port(), method, target, body, "", headers);
  }
  static std::int64_t start_live() {
    const HttpResult r = request("POST", "/api/runs", kAuth,
                                 json{{"scenario", small_scenario("joystick", 60)}, {"rate", 1}}.dump());
    EXPECT_EQ(r.status, 201) << r.body;
    return r.json().at("id").get<std::int64_t>();
  }
  static void stop(std::int64_t id) {
    EXPECT_EQ(request("POST", "/api/runs/" + std::to_string(id) + "/control", kAuth, R"({"action":"stop"})").status,
              200);
  }
  static inline std::unique_ptr<ServerProcess> server_;
};

void expect_unauthorized(const HttpResult& r, const std::string& what) {
  EXPECT_EQ(r.status, 401) << what << ": " << r.body;
  if (r.status != 401) return;
  EXPECT_EQ(error_of(r)["code"], "unauthorized") << what;
  EXPECT_NE(error_of(r)["message"].get<std::string>().find("Bearer"), std::string::npos) << what;
  EXPECT_EQ(r.headers.count("www-authenticate"), 1u) << what;
  EXPECT_EQ(r.content_type, "application/json") << what;
}

// Token guessing: after 20 wrong tokens in a minute an address gets 429 with
// Retry-After for every further wrong token; the right token still passes
// from the same address (before, 20 wrong tokens from any local process
// locked the holder out of 127.0.0.1); requests without a token are not affected.
TEST(TokenGuessing, TwentyWrongTokensAMinuteThen429ButTheRightOnePasses) {
  ServerProcess server("", {"--token", kToken});
  const Headers wrong = {{"Authorization", "Bearer guess"}};
  for (int i = 0; i < 20; ++i) EXPECT_EQ(http(server.port(), "GET", "/api/runs", "", "", wrong).status, 401) << i;
  const HttpResult slowed = http(server.port(), "GET", "/api/runs", "", "", wrong);
  EXPECT_EQ(slowed.status, 429) << slowed.body;
  EXPECT_EQ(error_of(slowed)["code"], "too_many_attempts");
  ASSERT_EQ(slowed.headers.count("retry-after"), 1u);
  const long wait = std::stol(slowed.headers.at("retry-after"));
  EXPECT_GT(wait, 0);
  EXPECT_LE(wait, 60);
  EXPECT_EQ(http(server.port(), "GET", "/api/runs", "", "", kAuth).status, 200) << "the holder is locked out";
  EXPECT_EQ(ws_upgrade(server.port(), "/ws/runs/1?token=guess").status, 429);
  EXPECT_NE(ws_upgrade(server.port(), "/ws/runs/1?token=" + kToken).status, 429);
  EXPECT_EQ(http(server.port(), "GET", "/api/health").status, 200);  // no token: not affected
  EXPECT_EQ(http(server.port(), "GET", "/").status, 200);
}


TEST_F(TokenServer, ChangesNeedTheToken) {
  const std::string run = json{{"scenario", small_scenario("joystick", 60)}, {"rate", 1}}.dump();
  const std::size_t before = request("GET", "/api/runs", kAuth).json().size();
  expect_unauthorized(request("POST", "/api/runs", {}, run), "POST without token");
  expect_unauthorized(request("POST", "/api/runs", {{"Authorization", "Bearer wrong"}}, run), "POST wrong token");
  expect_unauthorized(request("POST", "/api/runs", {{"Authorization", "Bearer " + kToken + "x"}}, run), "longer");
  expect_unauthorized(request("POST", "/api/runs", {{"Authorization", "Bearer " + kToken.substr(1)}}, run), "shorter");
  expect_unauthorized(request("POST", "/api/runs", {{"Authorization", "Basic " + kToken}}, run), "other scheme");
  expect_unauthorized(request("POST", "/api/runs", {{"Authorization", kToken}}, run), "no scheme");
  expect_unauthorized(request("DELETE", "/api/runs/1", {}), "DELETE");
  expect_unauthorized(request("PATCH", "/api/runs/1/params", {}, "{}"), "PATCH");
  // a token in the query does not count for REST (it would end up in logs and history)
  expect_unauthorized(request("POST", "/api/runs?token=" + kToken, {}, run), "query token on REST");
  EXPECT_EQ(request("GET", "/api/runs", kAuth).json().size(), before);

  const std::int64_t id = start_live();
  const std::string base = "/api/runs/" + std::to_string(id);
  expect_unauthorized(request("POST", base + "/joystick", {}, R"({"linear":[0.1,0]})"), "joystick");
  expect_unauthorized(request("POST", base + "/control", {}, R"({"action":"pause"})"), "control");
  EXPECT_EQ(request("POST", base + "/joystick", kAuth, R"({"linear":[0.1,0]})").status, 200);
  EXPECT_EQ(request("POST", base + "/joystick", {{"Authorization", "bearer  " + kToken + " "}}, R"({"linear":[0,0]})")
                .status,
            200);  // scheme case and spaces as RFC 7235 allows
  stop(id);
}

TEST_F(TokenServer, ReadsNeedTheTokenButHealthAndStaticFilesAreOpen) {
  expect_unauthorized(request("GET", "/api/runs", {}), "GET /api/runs");
  expect_unauthorized(request("GET", "/api/scenarios", {}), "GET /api/scenarios");
  EXPECT_EQ(request("HEAD", "/api/methods", {}).status, 401);  // a HEAD answer has no body to read
  expect_unauthorized(request("GET", "/api/health", {{"Authorization", "Bearer wrong"}}), "a wrong token anywhere");
  EXPECT_EQ(request("GET", "/api/runs", kAuth).status, 200);
  // open: the health check (container HEALTHCHECK) and the dashboard's files (it asks for the token)
  EXPECT_EQ(request("GET", "/api/health", {}).status, 200);
  EXPECT_EQ(request("GET", "/", {}).status, 200);
  EXPECT_EQ(request("GET", "/js/api.js", {}).status, 200);
  // the other rules still come first
  EXPECT_EQ(request("GET", "/api/runs", {{"Host", "evil.example:" + std::to_string(port())}}).status, 421);
  EXPECT_EQ(request("POST", "/api/runs", {{"Origin", "http://evil.example"}}, "{}").status, 403);
}

TEST_F(TokenServer, WebSocketsNeedTheTokenInTheHeaderOrTheQuery) {
  const std::int64_t id = start_live();
  const std::string ws = "/ws/runs/" + std::to_string(id);
  const HttpResult none = ws_upgrade(port(), ws);
  EXPECT_EQ(none.status, 401) << none.body;
  EXPECT_EQ(json::parse(none.body)["error"]["code"], "unauthorized");
  EXPECT_EQ(ws_upgrade(port(), ws + "?token=wrong").status, 401);
  EXPECT_EQ(ws_upgrade(port(), ws, {{"Authorization", "Bearer wrong"}}).status, 401);
  EXPECT_EQ(ws_upgrade(port(), ws + "?token=" + kToken).status, 101);
  EXPECT_EQ(ws_upgrade(port(), ws + "?client=tab-1&token=" + kToken).status, 101);
  EXPECT_EQ(ws_upgrade(port(), ws, kAuth).status, 101);
  // an authorised socket steers
  WsClient client(port(), ws + "?token=" + kToken);
  ASSERT_TRUE(client.read_type("snapshot"));
  client.send(R"({"type":"input","kind":"joystick","payload":{"linear":[0.1,0]}})");
  EXPECT_TRUE(client.read_type("ack"));
  stop(id);
}

TEST(TokenOptions, PublicReadOpensReadsAndWatchingButNotSteering) {
  ServerProcess server("", {"--token", kToken, "--public-read"});
  const unsigned short port = server.port();
  EXPECT_EQ(http(port, "GET", "/api/runs").status, 200);
  EXPECT_EQ(http(port, "GET", "/api/scenarios").status, 200);
  expect_unauthorized(http(port, "POST", "/api/runs", json{{"scenario", small_scenario("joystick", 60)}}.dump()),
                      "POST under --public-read");
  const HttpResult run = http(port, "POST", "/api/runs", json{{"scenario", small_scenario("joystick", 60)}}.dump(), "",
                              kAuth);
  ASSERT_EQ(run.status, 201) << run.body;
  const std::string id = std::to_string(run.json().at("id").get<std::int64_t>());
  // a tokenless socket watches: frames come, inputs are refused
  WsClient watcher(port, "/ws/runs/" + id);
  ASSERT_TRUE(watcher.read_type("snapshot"));
  watcher.send(R"({"type":"input","kind":"joystick","payload":{"linear":[0.1,0]}})");
  const auto refused = watcher.read_type("error");
  ASSERT_TRUE(refused);
  EXPECT_EQ((*refused)["error"]["code"], "unauthorized");
  watcher.send(R"({"type":"control","action":"stop"})");
  ASSERT_TRUE(watcher.read_type("error"));
  EXPECT_EQ(http(port, "GET", "/api/runs/" + id).json()["status"], "running");
  // a wrong token is refused even where none is needed
  EXPECT_EQ(ws_upgrade(port, "/ws/runs/" + id + "?token=wrong").status, 401);
  WsClient steerer(port, "/ws/runs/" + id + "?token=" + kToken);
  ASSERT_TRUE(steerer.read_type("snapshot"));
  steerer.send(R"({"type":"control","action":"stop"})");
  EXPECT_TRUE(steerer.read_type("ack"));
}

// The binary's exit code and everything it printed (stderr included).
CommandResult run_with_stderr(const std::string& env, const std::vector<std::string>& args) {
  std::string command = env + " " + RRLAB_BINARY;
  for (const auto& a : args) command += " '" + a + "'";
  command += " 2>&1";
  CommandResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  char buf[4096];
  size_t n = 0;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) result.out.append(buf, n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

TEST(TokenOptions, NonLoopbackBindWithoutTokenIsRefused) {
  const std::string dir = temp_dir();
  const std::vector<std::string> args = {"serve", "--host", "0.0.0.0", "--port", "0", "--db", dir + "/x.db"};
  const CommandResult refused = run_with_stderr("env -u RRLAB_TOKEN", args);
  EXPECT_EQ(refused.exit_code, 2) << refused.out;
  for (const std::string& words : {"refusing to serve 0.0.0.0 without a token", "RRLAB_TOKEN", "--token",
                                   "--allow-anonymous", "--host 127.0.0.1"})
    EXPECT_NE(refused.out.find(words), std::string::npos) << words << " not in: " << refused.out;
  EXPECT_FALSE(std::ifstream(dir + "/x.db").good()) << "refused before opening the database";
  // a bad token is refused too
  const CommandResult blank = run_with_stderr("env -u RRLAB_TOKEN", {"serve", "--port", "0", "--token", "a b"});
  EXPECT_EQ(blank.exit_code, 2);
  EXPECT_NE(blank.out.find("visible ASCII"), std::string::npos) << blank.out;
  // and a short one: its length is what makes guessing infeasible
  const CommandResult shorter = run_with_stderr("env -u RRLAB_TOKEN", {"serve", "--port", "0", "--token", "s3cret-token"});
  EXPECT_EQ(shorter.exit_code, 2);
  EXPECT_NE(shorter.out.find("shorter than 16 characters"), std::string::npos) << shorter.out;
  std::system(("rm -rf '" + dir + "'").c_str());
}

TEST(TokenOptions, NonLoopbackBindStartsWithATokenFromTheEnvironmentOrAllowAnonymous) {
  for (const std::string& how : {"env", "anonymous"}) {
    if (how == "env") setenv("RRLAB_TOKEN", kToken.c_str(), 1);
    ServerProcess server("", how == "env" ? std::vector<std::string>{"--host", "0.0.0.0", "--allow-host", "127.0.0.1"}
                                          : std::vector<std::string>{"--host", "0.0.0.0", "--allow-anonymous"});
    unsetenv("RRLAB_TOKEN");
    const std::string host = "127.0.0.1:" + std::to_string(server.port());
    EXPECT_EQ(http(server.port(), "GET", "/api/health", "", "", {{"Host", host}}).status, 200) << how;
    EXPECT_EQ(http(server.port(), "GET", "/api/runs", "", "", {{"Host", host}}).status, how == "env" ? 401 : 200)
        << how;
    EXPECT_EQ(http(server.port(), "GET", "/api/runs", "", "", {{"Host", host}, {"Authorization", "Bearer " + kToken}})
                  .status,
              200)
        << how;
  }
}

TEST(ConstantTimeEquals, EqualUnequalAndDifferentLengths) {
  using server::constant_time_equals;
  EXPECT_TRUE(constant_time_equals("", ""));
  EXPECT_TRUE(constant_time_equals(kToken, kToken));
  EXPECT_FALSE(constant_time_equals(kToken, "t3cret-Token_0123456789"));  // first byte
  EXPECT_FALSE(constant_time_equals(kToken, "s3cret-Token_0123456780"));  // last byte
  EXPECT_FALSE(constant_time_equals(kToken, kToken + "x"));
  EXPECT_FALSE(constant_time_equals(kToken + "x", kToken));
  EXPECT_FALSE(constant_time_equals(kToken, ""));
  EXPECT_FALSE(constant_time_equals("", kToken));
  EXPECT_FALSE(constant_time_equals(std::string("a\0", 2), "a"));  // a NUL is a byte like any other
  EXPECT_FALSE(constant_time_equals("ab", std::string("ab\0", 3)));
}

TEST(TokenTable, Decisions) {
  using server::AccessConfig;
  using server::AccessRequest;
  using server::check_access;
  AccessConfig config{"127.0.0.1", 8080, {}, {}, kToken, false};
  const std::string host = "127.0.0.1:8080", bearer = "Bearer " + kToken;
  const auto decide = [&](const std::string& method, const std::string& target, const std::string& auth,
                          bool upgrade = false) {
    return check_access(config, AccessRequest{method, target, host, "", "", false, upgrade, auth});
  };
  EXPECT_EQ(decide("GET", "/api/runs", "").status, 401);
  EXPECT_EQ(decide("GET", "/api/runs", bearer).status, 0);
  EXPECT_EQ(decide("GET", "/api/health", "").status, 0);
  EXPECT_EQ(decide("HEAD", "/api/health?x=1", "").status, 0);
  EXPECT_EQ(decide("POST", "/api/health", "").status, 401);
  EXPECT_EQ(decide("GET", "/index.html", "").status, 0);
  EXPECT_EQ(decide("POST", "/index.html", "").status, 401);
  EXPECT_EQ(decide("OPTIONS", "/api/runs", "").status, 401);
  EXPECT_EQ(decide("GET", "/ws/runs/1", "", true).status, 401);
  EXPECT_EQ(decide("GET", "/ws/runs/1?token=" + kToken, "", true).status, 0);
  EXPECT_EQ(decide("GET", "/ws/runs/1?client=a&token=" + kToken + "&x", "", true).status, 0);
  EXPECT_EQ(decide("GET", "/ws/runs/1?token=s3cret%2DToken_0123456789", "", true).status, 0);  // percent-encoded
  EXPECT_EQ(decide("GET", "/ws/runs/1?tokens=" + kToken, "", true).status, 401);
  EXPECT_EQ(decide("GET", "/ws/runs/1", bearer, true).status, 0);
  EXPECT_TRUE(decide("GET", "/ws/runs/1", bearer, true).may_steer);
  // a preflight (answered before the token rule) allows the headers the dashboard sends
  AccessConfig cors = config;
  cors.allow_origins = {"http://lab.example"};
  AccessRequest preflight{"OPTIONS", "/api/runs", host, "http://lab.example", "", false, false, ""};
  preflight.request_headers = "content-type, Authorization,rrlab-client, x-other";
  const auto allowed = check_access(cors, preflight);
  EXPECT_EQ(allowed.status, 204);
  std::string allow_headers;
  for (const auto& [name, value] : allowed.headers)
    if (name == "Access-Control-Allow-Headers") allow_headers = value;
  EXPECT_EQ(allow_headers, "Content-Type, Authorization, Rrlab-Client");
  config.public_read = true;
  EXPECT_EQ(decide("GET", "/api/runs", "").status, 0);
  EXPECT_EQ(decide("POST", "/api/runs", "").status, 401);
  EXPECT_EQ(decide("GET", "/ws/runs/1", "", true).status, 0);
  EXPECT_FALSE(decide("GET", "/ws/runs/1", "", true).may_steer);
  EXPECT_EQ(decide("GET", "/ws/runs/1?token=no", "", true).status, 401);
  config.token.clear();  // no token: everything as before
  EXPECT_EQ(decide("POST", "/api/runs", "").status, 0);
  EXPECT_TRUE(decide("GET", "/ws/runs/1", "", true).may_steer);

  EXPECT_EQ(server::token_problem(kToken), "");
  EXPECT_NE(server::token_problem(""), "");
  EXPECT_NE(server::token_problem("a b"), "");
  EXPECT_NE(server::token_problem(std::string(513, 'a')), "");
  EXPECT_TRUE(server::is_loopback_host("127.0.0.1"));
  EXPECT_TRUE(server::is_loopback_host("::1"));
  EXPECT_FALSE(server::is_loopback_host("0.0.0.0"));
  EXPECT_FALSE(server::is_loopback_host("::"));
}

}  // namespace
}  // namespace rrlab::testing
