// REST answers to scenarios whose URDF robot cannot be used: POST /api/runs,
// POST /api/scenarios and POST /api/scenarios/validate answer 422 with the
// JSON path (robot.urdf, robot.file, robot.base_link or robot.tip_link) and a
// message naming the joint, link or file; nothing is stored. The server's
// scenario directory is a fixture (support/urdf_faults.hpp) holding URDF
// files, a symbolic link out of it, and a file beside it.
#include <gtest/gtest.h>

#include <memory>
#include <nlohmann/json.hpp>

#include "client.hpp"
#include "server_process.hpp"
#include "urdf_faults.hpp"

namespace rrlab::testing {
namespace {

using nlohmann::json;
namespace uf = urdf_faults;

class UrdfRoutes : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    catalogue_ = std::make_unique<uf::Catalogue>();
    // a body limit above the URDF size limit, so that an oversize inline URDF reaches the scenario check
    server_ = std::make_unique<ServerProcess>("", std::vector<std::string>{"--scenarios", catalogue_->dir,
                                                                           "--body-limit", "4194304"});
  }
  static void TearDownTestSuite() {
    server_.reset();
    catalogue_.reset();
  }
  static HttpResult post(const std::string& target, const json& body) { return http_json(server_->port(), "POST", target, body); }

  // The three routes that take a scenario refuse it with 422 naming the path.
  static void expect_refused(const uf::Fault& fault, const json& doc) {
    const HttpResult run = post("/api/runs", {{"scenario", doc}, {"mode", "batch"}, {"steps", 1}});
    ASSERT_EQ(run.status, 422) << fault.name << ": " << run.body;
    const json error = run.json().at("error");
    EXPECT_EQ(error["code"], "invalid") << fault.name;
    EXPECT_EQ(error["path"], "scenario." + fault.path) << fault.name << ": " << run.body;
    EXPECT_NE(error["message"].get<std::string>().find(fault.message), std::string::npos) << fault.name << ": " << run.body;

    for (const char* route : {"/api/scenarios", "/api/scenarios/validate"}) {
      json named = doc;
      named["name"] = "urdf_fault_" + std::to_string(++stored_);
      const HttpResult r = post(route, named);
      ASSERT_EQ(r.status, 422) << fault.name << " " << route << ": " << r.body;
      EXPECT_EQ(r.json()["error"]["path"], fault.path) << fault.name << " " << route << ": " << r.body;
      EXPECT_NE(r.json()["error"]["message"].get<std::string>().find(fault.message), std::string::npos)
          << fault.name << " " << route << ": " << r.body;
      EXPECT_EQ(http(server_->port(), "GET", "/api/scenarios/" + named["name"].get<std::string>()).status, 404);
    }
  }

  static inline std::unique_ptr<uf::Catalogue> catalogue_;
  static inline std::unique_ptr<ServerProcess> server_;
  static inline int stored_ = 0;
};

TEST_F(UrdfRoutes, TheFixturesRunWhenNothingIsWrong) {
  for (const json& robot : {json{{"urdf", uf::chain()}}, json{{"file", "robots/good.urdf"}}}) {
    const HttpResult run = post("/api/runs", {{"scenario", uf::scenario(robot)}, {"mode", "batch"}, {"steps", 5}});
    ASSERT_EQ(run.status, 200) << run.body;
    EXPECT_EQ(run.json()["status"], "completed") << run.body;
    EXPECT_EQ(post("/api/scenarios/validate", uf::scenario(robot)).status, 200);
  }
}

TEST_F(UrdfRoutes, FaultsInInlineUrdfTextAre422NamingTheJointOrLink) {
  for (const uf::Fault& fault : uf::inline_faults()) expect_refused(fault, uf::scenario_for(fault));
}

TEST_F(UrdfRoutes, FilePathsOutsideTheScenarioDirectoryAndFaultyFilesAre422) {
  for (const uf::Fault& fault : catalogue_->file_faults()) expect_refused(fault, uf::scenario_for(fault));
}

TEST_F(UrdfRoutes, InlineTextOverTheSizeLimitIs422Or413) {
  std::string big = uf::chain();
  big.insert(big.find("</robot>"), "<!--" + std::string(1 << 20, 'x') + "-->");  // 1 MiB of comment
  const uf::Fault fault{"oversize", {}, "robot.urdf", "is longer than 1048576 bytes"};
  expect_refused(fault, uf::scenario({{"urdf", big}}));
  // with the default body limit (1 MiB, the same as the URDF's) the body is refused first
  ServerProcess plain;
  const HttpResult r = http_json(plain.port(), "POST", "/api/runs", {{"scenario", uf::scenario({{"urdf", big}})}});
  EXPECT_EQ(r.status, 413) << r.body;
  EXPECT_EQ(r.json()["error"]["code"], "body_too_large") << r.body;
}

}  // namespace
}  // namespace rrlab::testing
