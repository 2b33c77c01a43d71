// Scenario validation without saving (the dashboard's editor) and names that
// exist already: a scenario is never replaced.
#include <algorithm>
#include <string>
#include <vector>

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

// The start page's preview: the snapshot a run's stream starts with, of a
// catalogue scenario, without a run; bad and unknown names; nothing stored.
TEST_F(ScenarioRoutes, PreviewAnswersTheFirstSnapshotAndStoresNothing) {
  const size_t runs_before = get("/api/runs?limit=1000").json().size();
  const json scenarios_before = get("/api/scenarios?limit=1000").json()["total"];

  const HttpResult r = get("/api/scenarios/01_planar7_obstacles/preview");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(r.content_type, "application/json");
  const json p = r.json();
  EXPECT_EQ(p["type"], "snapshot");
  EXPECT_EQ(p["preview"], true);
  EXPECT_EQ(p["status"], "preview");
  EXPECT_TRUE(p["run"].is_null());
  EXPECT_EQ(p["scenario"], "01_planar7_obstacles");
  EXPECT_EQ(p["model"]["kind"], "planar");
  EXPECT_EQ(p["model"]["dof"], 7);
  EXPECT_EQ(p["obstacles"].size(), get("/api/scenarios/01_planar7_obstacles").json()["obstacles"].size());
  EXPECT_GT(p["task"]["path"].size(), 100u);  // the path sampled for drawing
  EXPECT_FALSE(p["param_specs"].empty());
  // frame 0 as a frame message draws it: one segment per link, each link's nearest obstacle
  const json& frame = p["frame"];
  EXPECT_EQ(frame["type"], "frame");
  EXPECT_EQ(frame["seq"], 0);
  EXPECT_EQ(frame["step"], 0);
  EXPECT_EQ(frame["status"], "preview");
  EXPECT_EQ(frame["links"].size(), 7u);
  EXPECT_EQ(frame["nearest"].size(), 7u);
  EXPECT_TRUE(frame.contains("ellipsoid"));

  // a name inside a file finds it too; a 3D arm's
  EXPECT_EQ(get("/api/scenarios/planar7_obstacles/preview").json()["scenario"], "01_planar7_obstacles");
  EXPECT_NE(get("/api/scenarios/03_dh7_pose/preview").json()["model"]["kind"], "planar");

  // unknown: 404 naming the scenario; malformed names: 400 naming the name
  const HttpResult unknown = get("/api/scenarios/no_such_scenario/preview");
  EXPECT_EQ(unknown.status, 404);
  EXPECT_EQ(error_of(unknown)["path"], "scenario");
  for (const std::string& bad : std::vector<std::string>{"bad%20name", "a$b", std::string(65, 'x')}) {
    const HttpResult malformed = get("/api/scenarios/" + bad + "/preview");
    EXPECT_EQ(malformed.status, 400) << bad << ": " << malformed.body;
    EXPECT_EQ(error_of(malformed)["path"], "name") << bad;
  }
  EXPECT_EQ(http(port(), "POST", "/api/scenarios/01_planar7_obstacles/preview", "{}").status, 405);

  // nothing stored: no run, no scenario
  EXPECT_EQ(get("/api/runs?limit=1000").json().size(), runs_before);
  EXPECT_EQ(get("/api/scenarios?limit=1000").json()["total"], scenarios_before);

  // the same frame 0 a run stores (the stream's 7 digits against exact values)
  const HttpResult run = send("POST", "/api/runs", {{"scenario", "01_planar7_obstacles"}, {"mode", "batch"}, {"steps", 1}});
  ASSERT_EQ(run.status, 200) << run.body;
  const json stored =
      get("/api/runs/" + std::to_string(run.json()["id"].get<int>()) + "/frames?from=0&to=0").json()["frames"].at(0);
  for (size_t i = 0; i < 7; ++i) EXPECT_NEAR(frame["q"][i].get<double>(), stored["q"][i].get<double>(), 1e-6);
  for (size_t i = 0; i < 3; ++i) EXPECT_NEAR(frame["ee"][i].get<double>(), stored["ee"][i].get<double>(), 1e-6);

  // a scenario added over REST previews as a file does
  json added = small_scenario("circle", 2.0);
  added["name"] = "previewed_after_adding";
  ASSERT_EQ(send("POST", "/api/scenarios", added).status, 201);
  const json small = get("/api/scenarios/previewed_after_adding/preview").json();
  EXPECT_EQ(small["scenario"], "previewed_after_adding");
  EXPECT_EQ(small["frame"]["links"].size(), 4u);
}

}  // namespace
}  // namespace rrlab::testing
