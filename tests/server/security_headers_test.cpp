// Static files carry a Content-Security-Policy that allows this server only
// and no inline script but the page's import map, by its hash
// (net/static_files.hpp); API answers carry no CORS header by default.
#include <rrlab/server/net/sha256.hpp>
#include <rrlab/server/net/static_files.hpp>

#include <fstream>
#include <sstream>

#include "server_fixture.hpp"

namespace rrlab::testing {
namespace {

std::string hex(const std::array<std::uint8_t, 32>& d) {
  std::string out;
  char buf[3];
  for (auto b : d) {
    std::snprintf(buf, sizeof buf, "%02x", b);
    out += buf;
  }
  return out;
}

TEST(Sha256, KnownVectors) {
  using server::sha256;
  // FIPS 180-4 examples, and lengths around the padding boundary (55, 56, 64 bytes)
  EXPECT_EQ(hex(sha256("")), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(hex(sha256("abc")), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(hex(sha256("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq")),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(hex(sha256(std::string(55, 'a'))), "9f4390f8d30c2dd92ec9f095b65e2b9ae9b0a925a5258e241c9f1e910f734318");
  EXPECT_EQ(hex(sha256(std::string(64, 'a'))), "ffe054fe7ae0cb6dc65c3af9b61d5209f439851db43d0ba5997337df154668eb");
  const std::uint8_t bytes[] = {'a', 'b', 'c'};
  EXPECT_EQ(server::base64(bytes, 3), "YWJj");
  EXPECT_EQ(server::base64(bytes, 2), "YWI=");
  EXPECT_EQ(server::base64(bytes, 1), "YQ==");
}

TEST(ContentSecurityPolicy, HashesOnlyTheImportMap) {
  const std::string page = "<script type=\"importmap\">{\"imports\":{}}</script><script>alert(1)</script>";
  const std::string csp = server::content_security_policy(page);
  const auto digest = server::sha256("{\"imports\":{}}");
  EXPECT_NE(csp.find("script-src 'self' 'sha256-" + server::base64(digest.data(), 32) + "';"), std::string::npos)
      << csp;
  EXPECT_EQ(csp.find("unsafe-inline"), std::string::npos);
  EXPECT_EQ(csp.find("unsafe-eval"), std::string::npos);
  EXPECT_NE(csp.find("style-src 'self';"), std::string::npos);
  EXPECT_NE(csp.find("frame-ancestors 'none'"), std::string::npos);
  EXPECT_EQ(server::content_security_policy("").find("sha256"), std::string::npos);
}

class SecurityHeaders : public ServerTest {};

TEST_F(SecurityHeaders, StaticFilesCarryThePolicy) {
  HttpResult page = get("/");
  ASSERT_EQ(page.status, 200);
  const std::string csp = page.headers["content-security-policy"];
  EXPECT_NE(csp.find("default-src 'self'"), std::string::npos) << csp;
  EXPECT_EQ(csp.find("unsafe-inline"), std::string::npos) << csp;
  // the hash is the served page's own import map
  std::ifstream in(std::string(RRLAB_SOURCE_DIR) + "/web/index.html");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(csp, server::content_security_policy(text.str()));
  EXPECT_NE(csp.find("'sha256-"), std::string::npos);
  EXPECT_EQ(page.headers["x-content-type-options"], "nosniff");
  EXPECT_EQ(page.headers["x-frame-options"], "DENY");
  EXPECT_EQ(page.headers["referrer-policy"], "no-referrer");
  HttpResult script = get("/js/main.js");
  EXPECT_NE(script.headers["content-security-policy"].find("default-src 'self'"), std::string::npos);
  EXPECT_EQ(script.headers["content-security-policy"].find("sha256"), std::string::npos);
  HttpResult head = http(port(), "HEAD", "/index.html");
  EXPECT_EQ(head.headers["content-security-policy"], csp);
  // no CORS by default
  HttpResult api = http(port(), "GET", "/api/health", "", "", {{"Origin", "http://lab.example"}});
  EXPECT_EQ(api.headers.count("access-control-allow-origin"), 0u);
  EXPECT_EQ(page.headers.count("access-control-allow-origin"), 0u);
}

}  // namespace
}  // namespace rrlab::testing
