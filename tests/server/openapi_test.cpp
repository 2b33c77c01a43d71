// GET /api/openapi.json against the router: every route the router knows is
// documented and every documented route is routed (the table from the router
// itself, api_routes()); every $ref resolves; the served document is the
// compiled one. (tests/server/openapi_readme_test.py validates the curl bodies
// of docs/api.md's examples against its schemas.)
#include <regex>
#include <set>

#include <rrlab/server/routes/routes.hpp>

#include "server_fixture.hpp"

namespace rrlab::testing {
namespace {

using nlohmann::json;

// "/api/runs/{id}/obstacles/{oid}" -> "/api/runs/{}/obstacles/{}", the router's spelling
std::string router_pattern(const std::string& documented) {
  return std::regex_replace(documented, std::regex("\\{[^}]+\\}"), "{}");
}

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::set<std::string> routed() {
  std::set<std::string> out;
  for (const server::RouteInfo& r : server::api_routes()) out.insert(lower(r.verb) + " " + r.pattern);
  return out;
}

std::set<std::string> documented(const json& doc) {
  static const std::set<std::string> verbs = {"get", "put", "post", "delete", "options", "head", "patch", "trace"};
  std::set<std::string> out;
  for (const auto& [path, item] : doc.at("paths").items())
    for (const auto& [verb, operation] : item.items())
      if (verbs.count(verb)) out.insert(verb + " " + router_pattern(path));
  return out;
}

TEST(OpenApi, EveryRoutedRouteIsDocumentedAndEveryDocumentedRouteIsRouted) {
  const std::set<std::string> router = routed();
  const std::set<std::string> document = documented(server::openapi_document());
  EXPECT_EQ(router.size(), 36u);  // the table in server/routes/router.cpp
  for (const std::string& route : router) EXPECT_TRUE(document.count(route)) << route << " is not in server/openapi.json";
  for (const std::string& route : document) EXPECT_TRUE(router.count(route)) << route << " is documented but not routed";
  EXPECT_EQ(router.size(), document.size());
}

TEST(OpenApi, EveryOperationHasAnIdParametersAndAnswers) {
  const json& doc = server::openapi_document();
  EXPECT_EQ(doc.at("openapi"), "3.1.0");
  std::set<std::string> ids;
  for (const auto& [path, item] : doc.at("paths").items()) {
    std::set<std::string> in_path;
    static const std::regex parameter("\\{([^}]+)\\}");
    for (std::sregex_iterator it(path.begin(), path.end(), parameter), end; it != end; ++it)
      in_path.insert((*it)[1]);
    for (const auto& [verb, op] : item.items()) {
      const std::string where = verb + " " + path;
      ASSERT_TRUE(op.contains("operationId")) << where;
      EXPECT_TRUE(ids.insert(op["operationId"].get<std::string>()).second) << where << ": operationId repeats";
      EXPECT_FALSE(op.value("summary", "").empty()) << where;
      std::set<std::string> declared;
      for (const json& p : op.value("parameters", json::array()))
        if (p.at("in") == "path") declared.insert(p.at("name").get<std::string>());
      EXPECT_EQ(declared, in_path) << where << ": path parameters";
      int success = 0;
      for (const auto& [status, answer] : op.at("responses").items()) {
        if (status[0] == '2') ++success;
        if (status[0] == '4' || status[0] == '5') {
          EXPECT_TRUE(answer.contains("$ref")) << where << " " << status;
        }
      }
      EXPECT_GE(success, 1) << where;
      // a body means 415 without Content-Type: application/json, so it is documented
      if (op.contains("requestBody")) {
        EXPECT_TRUE(op.at("responses").contains("415")) << where;
      }
    }
  }
}

void check_refs(const json& root, const json& node, const std::string& where, int& count) {
  if (node.is_object()) {
    for (const auto& [key, value] : node.items()) {
      if (key == "$ref" && value.is_string()) {
        ++count;
        const std::string ref = value.get<std::string>();
        ASSERT_EQ(ref.rfind("#/", 0), 0u) << where << ": " << ref << " is not local";
        EXPECT_TRUE(root.contains(json::json_pointer(ref.substr(1)))) << where << ": " << ref << " does not resolve";
      } else {
        check_refs(root, value, where + "/" + key, count);
      }
    }
  } else if (node.is_array()) {
    for (const json& item : node) check_refs(root, item, where, count);
  }
}

TEST(OpenApi, EveryRefResolvesInTheDocument) {
  const json& doc = server::openapi_document();
  int count = 0;
  check_refs(doc, doc, "", count);
  EXPECT_GT(count, 100);  // 200 or so: every answer, error and body schema
  // the scenario schema is the file format's (docs/scenario.schema.json), with its $defs alongside
  const json& schemas = doc.at("components").at("schemas");
  EXPECT_EQ(schemas.at("Scenario").at("required"), json({"robot", "task"}));
  EXPECT_TRUE(schemas.contains("Obstacle"));
  EXPECT_FALSE(schemas.at("Scenario").contains("$defs"));
}

class OpenApiServed : public ServerTest {};

TEST_F(OpenApiServed, TheRouteServesTheCompiledDocument) {
  const HttpResult r = get("/api/openapi.json");
  ASSERT_EQ(r.status, 200);
  EXPECT_EQ(r.content_type, "application/json");
  EXPECT_EQ(r.json(), server::openapi_document());
}

// Every documented route reaches its handler: an id that does not exist gives
// the handler's 404 (or a 400/409/415 for the body), never the router's
// "no API route" 404 nor 405.
TEST_F(OpenApiServed, EveryDocumentedRouteReachesAHandler) {
  const json& doc = server::openapi_document();
  int probed = 0;
  for (const auto& [path, item] : doc.at("paths").items()) {
    const std::string target = std::regex_replace(path, std::regex("\\{[^}]+\\}"), "999999");
    for (const auto& [verb, op] : item.items()) {
      std::string upper = verb;
      for (char& c : upper) c = char(std::toupper(static_cast<unsigned char>(c)));
      if (upper == "POST" && (path == "/api/runs" || path == "/api/compare" || path == "/api/sweeps" ||
                              path == "/api/scenarios"))
        continue;  // would start or store something: their routing is covered by routes_test
      const HttpResult r = http(port(), upper, target, op.contains("requestBody") ? "{}" : "");
      ++probed;
      EXPECT_NE(r.status, 405) << upper << " " << target;
      if (r.status == 404) {
        EXPECT_EQ(r.body.find("no API route"), std::string::npos) << upper << " " << target;
      }
    }
  }
  EXPECT_EQ(probed, 32);
}

}  // namespace
}  // namespace rrlab::testing
