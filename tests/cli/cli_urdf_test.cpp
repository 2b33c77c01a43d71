// `rrlab run` on a scenario whose URDF robot cannot be used: exit 2 and the
// message on stderr names the JSON path and the joint, link or file at fault.
// The faults (small URDF texts, a fixture scenario directory with a symbolic
// link out of it) are in support/urdf_faults.hpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "rrlab_command.hpp"
#include "urdf_faults.hpp"

namespace rrlab::testing {
namespace {

using nlohmann::json;
namespace uf = urdf_faults;

// Writes the scenario next to the fixture URDFs and runs one step of it.
CliRun run_in(const uf::Catalogue& catalogue, const json& doc) {
  const std::string file = catalogue.dir + "/scenario.json";
  std::ofstream(file) << doc.dump();
  return run_cli("run " + file + " --steps 1");
}

void expect_refused(const CliRun& r, const uf::Fault& fault) {
  EXPECT_EQ(r.code, 2) << fault.name << ": " << r.out << r.err;
  EXPECT_TRUE(r.out.empty()) << fault.name << ": " << r.out;  // no summary
  EXPECT_NE(r.err.find("rrlab: error: " + fault.path + ": "), std::string::npos) << fault.name << ": " << r.err;
  EXPECT_NE(r.err.find(fault.message), std::string::npos) << fault.name << ": " << r.err;
  // one line: urdfdom's own console output is kept out of stderr
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << fault.name << ": " << r.err;
}

TEST(CliUrdf, TheFixturesRunWhenNothingIsWrong) {
  const uf::Catalogue catalogue;
  for (const json& robot : {json{{"urdf", uf::chain()}}, json{{"file", "robots/good.urdf"}}}) {
    const CliRun r = run_in(catalogue, uf::scenario(robot));
    ASSERT_EQ(r.code, 0) << robot.dump().substr(0, 40) << ": " << r.err;
    EXPECT_EQ(json::parse(r.out)["steps"], 1);
  }
}

TEST(CliUrdf, FaultsInTheUrdfTextExitTwoNamingTheJointOrLink) {
  const uf::Catalogue catalogue;
  for (const uf::Fault& fault : uf::inline_faults()) expect_refused(run_in(catalogue, uf::scenario_for(fault)), fault);
}

TEST(CliUrdf, FilePathsOutsideTheScenarioDirectoryAndFaultyFilesExitTwo) {
  const uf::Catalogue catalogue;
  for (const uf::Fault& fault : catalogue.file_faults())
    expect_refused(run_in(catalogue, uf::scenario_for(fault)), fault);
}

TEST(CliUrdf, InlineTextOverTheSizeLimitExitsTwo) {
  const uf::Catalogue catalogue;
  std::string big = uf::chain();
  big.insert(big.find("</robot>"), "<!--" + std::string(1 << 20, 'x') + "-->");  // 1 MiB of comment
  expect_refused(run_in(catalogue, uf::scenario({{"urdf", big}})),
                 {"oversize", {}, "robot.urdf", "is longer than 1048576 bytes"});
}

}  // namespace
}  // namespace rrlab::testing
