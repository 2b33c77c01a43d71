// The per-run CSV's difficulty columns, from synthetic stored runs: the
// obstacle counts of witness.difficulty, empty where a case has none.
#include <gtest/gtest.h>

#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include <rrlab/sweep/summaries_csv.hpp>

namespace rrlab::sweep {
namespace {

// The CSV as rows of named fields (no field of these runs is quoted).
std::vector<std::map<std::string, std::string>> rows_of(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  const auto split = [](const std::string& l) {
    std::vector<std::string> out(1);
    for (char c : l) {
      if (c == ',') out.emplace_back();
      else out.back().push_back(c);
    }
    return out;
  };
  std::getline(in, line);
  const std::vector<std::string> header = split(line);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    const std::vector<std::string> fields = split(line);
    auto& row = rows.emplace_back();
    for (size_t i = 0; i < header.size() && i < fields.size(); ++i) row[header[i]] = fields[i];
  }
  return rows;
}

TEST(SummariesCsv, ObstacleCountsOfTheDifficulty) {
  std::vector<SweepCase> cases(2);
  std::vector<storage::SweepRunEntry> stored(2);
  for (size_t i = 0; i < 2; ++i) {
    cases[i].key = stored[i].row.key = "s/gen:fam:1:" + std::to_string(i) + "/pinv";
    cases[i].scenario_key = "gen:fam:1:" + std::to_string(i);
    cases[i].config_key = "pinv";
    cases[i].family = "fam";
    stored[i].run_id = std::int64_t(i) + 1;
    stored[i].summary_json = R"({"steps": 10})";
  }
  stored[0].difficulty_json = R"({"clearance": 0.05, "blocking_obstacles": 3, "tight_obstacles": 1})";
  std::ostringstream out;
  write_summaries_csv(out, cases, stored);
  const auto rows = rows_of(out.str());
  ASSERT_EQ(rows.size(), 2u) << out.str();
  EXPECT_EQ(rows[0].at("difficulty_blocking_obstacles"), "3");
  EXPECT_EQ(rows[0].at("difficulty_tight_obstacles"), "1");
  EXPECT_EQ(rows[0].at("difficulty_clearance"), "0.050000000000000003");
  EXPECT_EQ(rows[1].at("difficulty_blocking_obstacles"), "");  // no difficulty: empty
  EXPECT_EQ(rows[1].at("difficulty_tight_obstacles"), "");
  EXPECT_EQ(rows[1].at("step_us_p99"), "");  // the step times stay last
}

}  // namespace
}  // namespace rrlab::sweep
