// GET /api/frame-fields and the OpenAPI document take the frame field table
// (sim/frame_fields.hpp) and the generator registry as they are: a stored
// frame read over REST has exactly the table's stored fields, the document's
// Frame schema names them, and its generator enum is `rrlab generate --list`.
#include <functional>
#include <set>
#include <sstream>

#include "server_fixture.hpp"

namespace rrlab::testing {
namespace {

using nlohmann::json;

TEST(FrameFieldsRoute, ListsTheTableAndAStoredFrameHasItsStoredFields) {
  ServerProcess server;
  const json listed = http(server.port(), "GET", "/api/frame-fields").json();
  ASSERT_TRUE(listed["fields"].is_array()) << listed.dump();
  EXPECT_GE(listed["blob_version"].get<int>(), 2);
  std::set<std::string> stored_top = {"seq"}, stored_metrics;
  for (const json& field : listed["fields"]) {
    bool stored = false, in_json = false;
    for (const json& output : field["outputs"]) stored |= output == "stored", in_json |= output == "json";
    if (!stored || !in_json) continue;
    (field["metric"].get<bool>() ? stored_metrics : stored_top).insert(field["name"].get<std::string>());
  }
  EXPECT_TRUE(stored_metrics.count("task_error"));
  EXPECT_FALSE(stored_metrics.count("step_us"));  // measured, never stored

  // a stored frame, as the REST API reads it back
  const json batch = {{"scenario", small_scenario("circle", 0.05)}, {"mode", "batch"}};
  const HttpResult run = http(server.port(), "POST", "/api/runs", batch.dump());
  ASSERT_EQ(run.status, 200) << run.body;
  const std::string id = std::to_string(run.json()["id"].get<long>());
  const json frames = http(server.port(), "GET", "/api/runs/" + id + "/frames").json();
  ASSERT_FALSE(frames["frames"].empty()) << frames.dump();
  const json& frame = frames["frames"][0];
  std::set<std::string> top, metrics;
  for (const auto& [key, value] : frame.items())
    if (key != "metrics") top.insert(key);
  for (const auto& [key, value] : frame["metrics"].items()) metrics.insert(key);
  stored_top.insert("metrics");
  top.insert("metrics");
  EXPECT_EQ(top, stored_top);
  EXPECT_EQ(metrics, stored_metrics);

  // the served document's Frame schema is the same list
  const json doc = http(server.port(), "GET", "/api/openapi.json").json();
  const json& schema = doc["components"]["schemas"]["Frame"];
  std::set<std::string> documented, documented_metrics;
  for (const auto& [key, value] : schema["properties"].items()) documented.insert(key);
  for (const auto& [key, value] : schema["properties"]["metrics"]["properties"].items()) documented_metrics.insert(key);
  EXPECT_EQ(documented, stored_top);
  EXPECT_EQ(documented_metrics, stored_metrics);
  EXPECT_EQ(server.stop(), 0);
}

TEST(FrameFieldsRoute, TheDocumentsGeneratorEnumIsTheRegistry) {
  const CommandResult listed = run_rrlab({"generate", "--list"});
  ASSERT_EQ(listed.exit_code, 0) << listed.out;
  json families = json::array();
  std::istringstream lines(listed.out);
  for (std::string line; std::getline(lines, line);)
    if (!line.empty()) families.push_back(line.substr(0, line.find('\t')));
  ASSERT_GE(families.size(), 7u);
  ServerProcess server;
  const json doc = http(server.port(), "GET", "/api/openapi.json").json();
  int enums = 0;
  std::function<void(const json&)> walk = [&](const json& node) {
    if (node.is_object()) {
      for (const auto& [key, value] : node.items()) {
        if (key == "generator" && value.is_object() && value.contains("enum")) {
          EXPECT_EQ(value["enum"], families);
          ++enums;
        } else {
          walk(value);
        }
      }
    } else if (node.is_array()) {
      for (const json& item : node) walk(item);
    }
  };
  walk(doc);
  EXPECT_GE(enums, 1);
  EXPECT_EQ(server.stop(), 0);
}

}  // namespace
}  // namespace rrlab::testing
