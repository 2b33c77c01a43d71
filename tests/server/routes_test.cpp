// Every REST route: success, and each error code with the bad field named.
#include "server_fixture.hpp"

#include <rrlab/scenario/scenario.hpp>

namespace rrlab::testing {
namespace {

using nlohmann::json;

class Routes : public ServerTest {};

TEST_F(Routes, HealthAndMethods) {
  const HttpResult health = get("/api/health");
  EXPECT_EQ(health.status, 200);
  EXPECT_EQ(health.content_type, "application/json");
  EXPECT_EQ(health.json()["status"], "ok");
  EXPECT_TRUE(health.json().contains("version"));
  const HttpResult methods = get("/api/methods");
  ASSERT_EQ(methods.status, 200);
  bool has_dls = false;
  for (const json& m : methods.json()) has_dls = has_dls || m["name"] == "dls";
  EXPECT_TRUE(has_dls);
}

TEST_F(Routes, UnknownPathsAndVerbs) {
  EXPECT_EQ(get("/api/nothing").status, 404);
  const HttpResult wrong_verb = http(port(), "DELETE", "/api/methods");
  EXPECT_EQ(wrong_verb.status, 405);
  EXPECT_EQ(error_of(wrong_verb)["code"], "method_not_allowed");
}

TEST_F(Routes, Scenarios) {
  const HttpResult list = get("/api/scenarios");
  ASSERT_EQ(list.status, 200);
  EXPECT_GE(list.json().at("scenarios").size(), 3u);
  EXPECT_EQ(get("/api/scenarios/01_planar7_obstacles").status, 200);
  const HttpResult missing = get("/api/scenarios/none");
  EXPECT_EQ(missing.status, 404);
  EXPECT_EQ(error_of(missing)["path"], "scenario");

  json added = small_scenario("circle", 1.0);
  added["name"] = "routes_added";
  EXPECT_EQ(send("POST", "/api/scenarios", added).status, 201);
  EXPECT_EQ(get("/api/scenarios/routes_added").json()["name"], "routes_added");
  EXPECT_EQ(send("POST", "/api/scenarios", added).status, 409);  // exists
  json invalid = added;
  invalid["name"] = "routes_invalid";
  invalid["robot"]["links"][2]["length"] = -1;
  const HttpResult bad = send("POST", "/api/scenarios", invalid);
  EXPECT_EQ(bad.status, 422);
  EXPECT_EQ(error_of(bad)["path"], "robot.links[2].length");
  invalid["name"] = "../../etc/passwd";
  EXPECT_EQ(error_of(send("POST", "/api/scenarios", invalid))["path"], "name");
}

TEST_F(Routes, MalformedAndTooLargeBodies) {
  const HttpResult malformed = http(port(), "POST", "/api/runs", "{\"scenario\": ");
  EXPECT_EQ(malformed.status, 400);
  EXPECT_EQ(error_of(malformed)["code"], "malformed_json");
  const HttpResult empty = http(port(), "POST", "/api/runs", "");
  EXPECT_EQ(empty.status, 400);
  const std::string huge = "{\"scenario\": \"" + std::string(2 << 20, 'x') + "\"}";
  const HttpResult too_large = http(port(), "POST", "/api/runs", huge);
  EXPECT_EQ(too_large.status, 413);
}

TEST_F(Routes, ClientBytesThatAreNotUtf8AreAnsweredNotFatal) {
  // error messages quote the path and the parser's "last read"; invalid UTF-8 must not crash the JSON writer
  EXPECT_EQ(get("/api/runs/\xff\xfe").status, 404);
  EXPECT_EQ(get("/\xff.html").status, 404);
  EXPECT_EQ(get("/api/scenarios/\xc3\x28").status, 404);
  EXPECT_EQ(http(port(), "POST", "/api/runs", "{\"scenario\": \"\xff").status, 400);
  EXPECT_EQ(get("/api/health").status, 200);  // still serving
}

TEST_F(Routes, StartRunErrorsNameTheField) {
  const auto path_of = [](const HttpResult& r) { return error_of(r)["path"].get<std::string>(); };
  HttpResult r = send("POST", "/api/runs", {{"scenario", "nope"}});
  EXPECT_EQ(r.status, 404);
  EXPECT_EQ(path_of(r), "scenario");
  r = send("POST", "/api/runs", {{"scenario", "01_planar7_obstacles"}, {"method", "magic"}});
  EXPECT_EQ(r.status, 400);
  EXPECT_EQ(path_of(r), "method");
  r = send("POST", "/api/runs", {{"scenario", "01_planar7_obstacles"}, {"method", "dls"}, {"params", {{"lambda", -3}}}});
  EXPECT_EQ(r.status, 400);
  EXPECT_EQ(path_of(r), "params.lambda");
  r = send("POST", "/api/runs", {{"scenario", "01_planar7_obstacles"}, {"mode", "turbo"}});
  EXPECT_EQ(r.status, 400);
  EXPECT_EQ(path_of(r), "mode");
  r = send("POST", "/api/runs", {{"scenario", "01_planar7_obstacles"}, {"colour", 1}});
  EXPECT_EQ(r.status, 400);
  EXPECT_EQ(path_of(r), "colour");
  r = send("POST", "/api/runs", {{"scenario", "01_planar7_obstacles"}, {"steps", 0}});
  EXPECT_EQ(path_of(r), "steps");
  json inline_bad = small_scenario();
  inline_bad["robot"]["q0"] = {1, 2};
  r = send("POST", "/api/runs", {{"scenario", inline_bad}});
  EXPECT_EQ(r.status, 422);
  EXPECT_EQ(path_of(r), "scenario.robot.q0");
  r = send("POST", "/api/runs", json::array());
  EXPECT_EQ(r.status, 400);
}

// A mesh obstacle's file in a scenario sent over REST resolves in the
// catalogue (--scenarios) and may not leave it.
TEST_F(Routes, MeshObstacleFilesStayInTheCatalogue) {
  json scenario = read_json_file(std::string(RRLAB_SOURCE_DIR) + "/scenarios/43_urdf_iiwa14_mesh_obstacle.json", "scenario");
  scenario["obstacles"][0]["file"] = "../README.md";
  HttpResult r = send("POST", "/api/runs", {{"scenario", scenario}});
  EXPECT_EQ(r.status, 422) << r.body;
  EXPECT_EQ(error_of(r)["path"], "scenario.obstacles[0].file");
  EXPECT_NE(error_of(r)["message"].get<std::string>().find("\"../README.md\" leads outside the scenario directory"),
            std::string::npos)
      << r.body;
  scenario["obstacles"][0]["file"] = "meshes/../../README.md";
  r = send("POST", "/api/runs", {{"scenario", scenario}});
  EXPECT_EQ(r.status, 422) << r.body;
  EXPECT_EQ(error_of(r)["path"], "scenario.obstacles[0].file");
  scenario["obstacles"][0]["file"] = "meshes/torus.obj";
  r = send("POST", "/api/runs", {{"scenario", scenario}, {"mode", "batch"}, {"steps", 20}});
  EXPECT_EQ(r.status, 200) << r.body;  // a batch run answers with its summary
  EXPECT_EQ(r.json()["summary"]["nonfinite_steps"], 0);
  // a live run takes live mesh obstacles
  r = send("POST", "/api/runs", {{"scenario", "43_urdf_iiwa14_mesh_obstacle"}, {"mode", "live"}, {"rate", 0.1}});
  ASSERT_EQ(r.status, 201) << r.body;
  const std::int64_t id = r.json().at("id").get<std::int64_t>();
  // a live obstacle_add of a mesh: resolved in the catalogue too, confined alike
  r = send("POST", "/api/runs/" + std::to_string(id) + "/obstacles",
           {{"id", "ring"}, {"shape", "mesh"}, {"file", "../README.md"}, {"center", {0.5, 0.5, 0.5}}});
  EXPECT_EQ(r.status, 400) << r.body;  // a live input's error, as for the other shapes
  EXPECT_EQ(error_of(r)["path"], "file");
  r = send("POST", "/api/runs/" + std::to_string(id) + "/obstacles",
           {{"id", "ring"}, {"shape", "mesh"}, {"file", "meshes/torus.obj"}, {"center", {0.5, 0.5, 0.5}}});
  EXPECT_LT(r.status, 300) << r.body;
  EXPECT_EQ(send("POST", "/api/runs/" + std::to_string(id) + "/control", {{"action", "stop"}}).status, 200);
}

TEST_F(Routes, BatchRunReturnsItsSummaryAndStoresFrames) {
  const HttpResult r = send("POST", "/api/runs", {{"scenario", "01_planar7_obstacles"}, {"mode", "batch"}, {"method", "dls"}});
  ASSERT_EQ(r.status, 200) << r.body;
  const json body = r.json();
  EXPECT_EQ(body["status"], "completed");
  const std::int64_t id = body["id"];
  const json summary = body["summary"];
  for (const char* key : {"scenario", "method", "steps", "collided", "min_distance", "max_tracking_error",
                          "final_tracking_error", "joint_limit_violated", "min_joint_limit_margin", "max_qdot_ratio",
                          "max_qddot_ratio", "max_condition_number", "rms_qddot", "max_qddot", "rms_jerk", "max_jerk",
                          "position_limit_steps", "velocity_limit_steps", "final_q", "step_us"})
    EXPECT_TRUE(summary.contains(key)) << key;
  const long steps = summary["steps"];

  const json run = get("/api/runs/" + std::to_string(id)).json();
  EXPECT_EQ(run["frames"], steps);
  EXPECT_EQ(run["method"], "dls");
  EXPECT_EQ(run["mode"], "batch");

  const HttpResult frames = get("/api/runs/" + std::to_string(id) + "/frames?from=10&to=20&stride=5");
  ASSERT_EQ(frames.status, 200);
  ASSERT_EQ(frames.json()["frames"].size(), 3u);
  EXPECT_EQ(frames.json()["frames"][1]["seq"], 15);
  EXPECT_EQ(frames.json()["frames"][1]["q"].size(), 7u);
  const HttpResult csv = get("/api/runs/" + std::to_string(id) + "/frames?to=1", "text/csv");
  EXPECT_EQ(csv.content_type, "text/csv");
  EXPECT_EQ(csv.body.rfind("seq,step,t,q1,", 0), 0u) << csv.body.substr(0, 80);
  EXPECT_EQ(std::count(csv.body.begin(), csv.body.end(), '\n'), 3);
  EXPECT_EQ(error_of(get("/api/runs/" + std::to_string(id) + "/frames?stride=0"))["path"], "stride");
  EXPECT_EQ(get("/api/runs/999999/frames").status, 404);
  EXPECT_EQ(get("/api/runs/abc").status, 404);

  // the list filters by method and scenario
  const json listed = get("/api/runs?method=dls&limit=5").json();
  ASSERT_FALSE(listed.empty());
  for (const json& r2 : listed) EXPECT_EQ(r2["method"], "dls");
  EXPECT_EQ(error_of(get("/api/runs?limit=0"))["path"], "limit");

  // inputs to a finished run: 409
  const HttpResult late = send("POST", "/api/runs/" + std::to_string(id) + "/control", {{"action", "start"}});
  EXPECT_EQ(late.status, 409);
}

TEST_F(Routes, LiveRunInputsAndTheirErrors) {
  const std::int64_t id = start_live({{"scenario", small_scenario("circle", 600)}, {"paused", true}});
  const std::string base = "/api/runs/" + std::to_string(id);
  // joystick on a circle task: 409
  HttpResult r = send("POST", base + "/joystick", {{"linear", {0.1, 0}}});
  EXPECT_EQ(r.status, 409);
  EXPECT_EQ(error_of(r)["code"], "wrong_state");
  // params
  r = send("PATCH", base + "/params", {{"gain", 3.5}});
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(r.json()["params"]["gain"], 3.5);
  r = send("PATCH", base + "/params", {{"gain", "high"}});
  EXPECT_EQ(r.status, 400);
  EXPECT_EQ(error_of(r)["path"], "gain");
  // obstacles
  r = send("PUT", base + "/obstacles/ball", {{"position", {0.3, 1.1}}});
  EXPECT_EQ(r.status, 200) << r.body;
  r = send("PUT", base + "/obstacles/ghost", {{"position", {0.3, 1.1}}});
  EXPECT_EQ(r.status, 404);
  r = send("PUT", base + "/obstacles/ball", {{"radius", 0}});
  EXPECT_EQ(r.status, 400);
  EXPECT_EQ(error_of(r)["path"], "radius");
  r = send("POST", base + "/obstacles", {{"id", "wall1"}, {"shape", "wall"}, {"point", {0, -0.5}}, {"normal", {0, 1}}});
  EXPECT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(http(port(), "DELETE", base + "/obstacles/wall1").status, 200);
  EXPECT_EQ(http(port(), "DELETE", base + "/obstacles/wall1").status, 404);
  // method switch
  r = send("POST", base + "/method", {{"name", "dls"}});
  EXPECT_EQ(r.status, 200);
  EXPECT_EQ(r.json()["method"], "dls");
  // control
  r = send("POST", base + "/control", {{"action", "fly"}});
  EXPECT_EQ(error_of(r)["path"], "action");
  r = send("POST", base + "/control", {{"rate", -1}});
  EXPECT_EQ(error_of(r)["path"], "rate");
  r = send("POST", base + "/control", {{"action", "step"}});
  ASSERT_EQ(r.status, 200);
  EXPECT_EQ(r.json()["step"], 1);
  r = send("POST", base + "/control", {{"action", "start"}});
  EXPECT_EQ(r.json()["status"], "running");
  r = send("POST", base + "/control", {{"action", "step"}});
  EXPECT_EQ(r.status, 409);  // not paused
  // events were stored with their kinds
  const json events = get(base + "/events").json();
  std::vector<std::string> kinds;
  for (const json& e : events) kinds.push_back(e["kind"]);
  EXPECT_EQ(kinds, (std::vector<std::string>{"params", "obstacle", "obstacle_add", "obstacle_remove", "method"}));
  EXPECT_EQ(send("POST", base + "/control", {{"action", "stop"}}).status, 200);
  EXPECT_EQ(wait_ended(id)["status"], "stopped");
}

TEST_F(Routes, CompareRunsMethodsInLockstep) {
  const HttpResult r = send("POST", "/api/compare",
                            {{"scenario", "01_planar7_obstacles"},
                             {"methods", {"pinv", {{"name", "dls"}, {"params", {{"lambda", 0.1}}}}, "closest_point"}},
                             {"steps", 200}});
  ASSERT_EQ(r.status, 200) << r.body;
  const json body = r.json();
  ASSERT_EQ(body["runs"].size(), 3u);
  ASSERT_EQ(body["comparison"].size(), 3u);
  EXPECT_EQ(body["comparison"][1]["method"], "dls");
  for (const json& run : body["runs"]) {
    const json stored = get("/api/runs/" + std::to_string(run["id"].get<long>())).json();
    EXPECT_EQ(stored["frames"], 200);
    EXPECT_EQ(stored["compare_group"], body["group"]);
  }
  EXPECT_EQ(error_of(send("POST", "/api/compare", {{"scenario", "01_planar7_obstacles"}, {"methods", {"pinv"}}}))["path"],
            "methods");
  EXPECT_EQ(error_of(send("POST", "/api/compare", {{"scenario", "01_planar7_obstacles"}, {"methods", {"pinv", "nah"}}}))["path"],
            "methods[1]");
}

TEST_F(Routes, RecordExportRunsAgainFromTheCommandLine) {
  const HttpResult batch = send("POST", "/api/runs", {{"scenario", "02_spatial_xz_reach"}, {"mode", "batch"}, {"steps", 150}});
  ASSERT_EQ(batch.status, 200) << batch.body;
  const std::int64_t id = batch.json()["id"];
  const HttpResult record = get("/api/runs/" + std::to_string(id) + "/record");
  ASSERT_EQ(record.status, 200);
  EXPECT_EQ(record.json()["rrlab_record"], 1);
  const std::string file = temp_dir() + "/record.json";
  {
    std::FILE* f = std::fopen(file.c_str(), "w");
    std::fputs(record.body.c_str(), f);
    std::fclose(f);
  }
  const CommandResult rerun = run_rrlab({"run", file});
  ASSERT_EQ(rerun.exit_code, 0);
  const json summary = json::parse(rerun.out);
  EXPECT_EQ(summary["steps"], 150);
  EXPECT_EQ(summary["final_q"], batch.json()["summary"]["final_q"]);  // the same run, bit for bit
}

TEST_F(Routes, StaticFilesWithMimeTypesAndNoTraversal) {
  const HttpResult index = get("/");
  EXPECT_EQ(index.status, 200);
  EXPECT_EQ(index.content_type, "text/html; charset=utf-8");
  EXPECT_EQ(get("/js/main.js").content_type, "text/javascript; charset=utf-8");
  EXPECT_EQ(get("/style.css").content_type, "text/css; charset=utf-8");
  EXPECT_EQ(get("/../CMakeLists.txt").status, 404);
  EXPECT_EQ(get("/%2e%2e/CMakeLists.txt").status, 404);
  EXPECT_EQ(get("/..%2fCMakeLists.txt").status, 404);
  EXPECT_EQ(get("/nothing.html").status, 404);
  EXPECT_EQ(http(port(), "POST", "/index.html", "{}").status, 405);
}

}  // namespace
}  // namespace rrlab::testing
