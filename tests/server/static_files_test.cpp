// The dashboard's files and its npm packages (web/node_modules, loaded through
// an import map): MIME types and caching.
#include <filesystem>

#include "server_fixture.hpp"

namespace rrlab::testing {
namespace {

class StaticFiles : public ServerTest {};

TEST_F(StaticFiles, RevalidatedEveryLoadAndNotSentAgainWhenUnchanged) {
  const HttpResult index = get("/index.html");
  ASSERT_EQ(index.status, 200);
  EXPECT_EQ(index.headers.at("cache-control"), "no-cache");
  const std::string etag = index.headers.at("etag");
  EXPECT_EQ(etag.front(), '"');
  const HttpResult unchanged = http(port(), "GET", "/index.html", "", "", {{"If-None-Match", etag}});
  EXPECT_EQ(unchanged.status, 304);
  EXPECT_TRUE(unchanged.body.empty());
  EXPECT_EQ(unchanged.headers.at("etag"), etag);
  EXPECT_EQ(http(port(), "GET", "/index.html", "", "", {{"If-None-Match", "\"other\""}}).status, 200);
  const HttpResult head = http(port(), "HEAD", "/style.css");
  EXPECT_EQ(head.status, 200);
  EXPECT_EQ(head.headers.at("cache-control"), "no-cache");
}

TEST_F(StaticFiles, NpmPackagesWithJavaScriptMimeTypes) {
  const std::string modules = std::string(RRLAB_SOURCE_DIR) + "/web/node_modules";
  if (!std::filesystem::is_directory(modules + "/three") || !std::filesystem::is_directory(modules + "/uplot"))
    FAIL() << "web/node_modules has no three or uplot: run scripts/install-deps (npm ci in web/), as make test does";
  for (const char* path : {"/node_modules/three/build/three.module.js", "/node_modules/three/build/three.core.js",
                           "/node_modules/uplot/dist/uPlot.esm.js"}) {
    const HttpResult file = get(path);
    EXPECT_EQ(file.status, 200) << path;
    EXPECT_EQ(file.content_type, "text/javascript; charset=utf-8") << path;
    EXPECT_EQ(file.headers.at("cache-control"), "no-cache") << path;
    EXPECT_GT(file.body.size(), 10000u) << path;
  }
  // three.module.js imports its core by a relative path that resolves here
  EXPECT_NE(get("/node_modules/three/build/three.module.js").body.find("./three.core.js"), std::string::npos);
  const std::string css = std::filesystem::exists(modules + "/uplot/dist/uPlot.css") ? "uPlot.css" : "uPlot.min.css";
  const HttpResult style = get("/node_modules/uplot/dist/" + css);
  EXPECT_EQ(style.status, 200);
  EXPECT_EQ(style.content_type, "text/css; charset=utf-8");
}

}  // namespace
}  // namespace rrlab::testing
