// Scenario validation without saving (the dashboard's editor) and names that
// exist already: a scenario is never replaced.
#include <algorithm>

#include "server_fixture.hpp"

namespace rrlab::testing {
namespace {

using nlohmann::json;

class ScenarioRoutes : public ServerTest {};

TEST_F(ScenarioRoutes, ValidateAnswersWhatARunWouldTakeAndStoresNothing) {
  json scenario = small_scenario("circle", 2.0);
  scenario["name"] = "validated_only";
  const HttpResult ok = send("POST", "/api/scenarios/validate", scenario);
  ASSERT_EQ(ok.status, 200) << ok.body;
  const json answer = ok.json();
  EXPECT_EQ(answer["valid"], true);
  EXPECT_EQ(answer["name"], "validated_only");
  EXPECT_EQ(answer["exists"], false);
  EXPECT_EQ(answer["dof"], 4);
  EXPECT_EQ(answer["links"], 4);
  EXPECT_EQ(answer["obstacles"], 1);
  EXPECT_EQ(answer["task"]["space"], "xy");
  EXPECT_EQ(answer["method"], "gpm");
  EXPECT_EQ(answer["steps"], 200);
  EXPECT_EQ(get("/api/scenarios/validated_only").status, 404);  // nothing stored

  // a catalogue scenario validates, and says its name is taken
  const json file = get("/api/scenarios/01_planar7_obstacles").json();
  const HttpResult existing = send("POST", "/api/scenarios/validate", file);
  ASSERT_EQ(existing.status, 200);
  EXPECT_EQ(existing.json()["exists"], true);
}

TEST_F(ScenarioRoutes, ValidateNamesTheJsonPath) {
  json scenario = small_scenario("circle", 2.0);
  scenario["robot"]["links"][3]["length"] = 0;
  HttpResult bad = send("POST", "/api/scenarios/validate", scenario);
  EXPECT_EQ(bad.status, 422);
  EXPECT_EQ(error_of(bad)["code"], "invalid");
  EXPECT_EQ(error_of(bad)["path"], "robot.links[3].length");

  // a parameter checked against the arm only when the simulator is built
  scenario = small_scenario("circle", 2.0);
  scenario["method"] = {{"name", "ccp_voronoi"}, {"params", {{"ccp_link", 9}}}};
  bad = send("POST", "/api/scenarios/validate", scenario);
  EXPECT_EQ(bad.status, 422) << bad.body;
  EXPECT_EQ(error_of(bad)["path"], "method.params.ccp_link");

  bad = send("POST", "/api/scenarios/validate", json::array({1, 2}));
  EXPECT_EQ(bad.status, 422);
  const HttpResult malformed = http(port(), "POST", "/api/scenarios/validate", "{\"robot\":");
  EXPECT_EQ(malformed.status, 400);
  EXPECT_EQ(error_of(malformed)["code"], "malformed_json");

  // the literal route comes before /api/scenarios/{name}
  EXPECT_EQ(error_of(get("/api/scenarios/validate"))["path"], "scenario");  // no scenario of that name
  EXPECT_EQ(http(port(), "PUT", "/api/scenarios/validate", "{}").status, 405);
}

TEST_F(ScenarioRoutes, ExistingNamesAreNeverReplaced) {
  // a file of scenarios/, by its stem
  json scenario = small_scenario("circle", 2.0);
  scenario["name"] = "01_planar7_obstacles";
  HttpResult conflict = send("POST", "/api/scenarios", scenario);
  EXPECT_EQ(conflict.status, 409);
  EXPECT_EQ(error_of(conflict)["code"], "exists");
  EXPECT_EQ(error_of(conflict)["path"], "name");
  EXPECT_EQ(get("/api/scenarios/01_planar7_obstacles").json()["robot"]["links"].size(), 7u);  // unchanged

  // one added earlier over REST
  scenario["name"] = "added_once";
  ASSERT_EQ(send("POST", "/api/scenarios", scenario).status, 201);
  json changed = scenario;
  changed["duration"] = 3.0;
  conflict = send("POST", "/api/scenarios", changed);
  EXPECT_EQ(conflict.status, 409);
  EXPECT_EQ(get("/api/scenarios/added_once").json()["duration"], 2.0);
  EXPECT_EQ(send("POST", "/api/scenarios/validate", changed).json()["exists"], true);
}

TEST_F(ScenarioRoutes, ACatalogueScenarioHasOneNameInTheListItsDocumentAndItsRuns) {
  const json listed = get("/api/scenarios?limit=1000").json()["scenarios"];
  const bool in_list = std::any_of(listed.begin(), listed.end(), [](const json& s) { return s["name"] == "01_planar7_obstacles"; });
  EXPECT_TRUE(in_list);
  EXPECT_EQ(get("/api/scenarios/01_planar7_obstacles").json()["name"], "01_planar7_obstacles");
  // the name inside the file still finds it, under the file's name
  EXPECT_EQ(get("/api/scenarios/planar7_obstacles").json()["name"], "01_planar7_obstacles");

  for (const char* asked : {"01_planar7_obstacles", "planar7_obstacles"}) {
    const HttpResult run = send("POST", "/api/runs", {{"scenario", asked}, {"mode", "batch"}, {"steps", 5}});
    ASSERT_EQ(run.status, 200) << run.body;  // a batch run answers when it has ended
    const json record = get("/api/runs/" + std::to_string(run.json()["id"].get<int>())).json();
    EXPECT_EQ(record["scenario"], "01_planar7_obstacles") << "asked for " << asked;
  }
  const json found = get("/api/runs?scenario=01_planar7_obstacles").json();
  EXPECT_EQ(found.size(), 2u);
  EXPECT_EQ(get("/api/runs?scenario=planar7_obstacles").json().size(), 0u);
}

}  // namespace
}  // namespace rrlab::testing
