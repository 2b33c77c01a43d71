// The committed benchmark is what the code gives: 2 cases of every family of
// benchmarks/default.json, every configuration, re-run here, match their rows
// of the committed per-run CSV (benchmarks/default-runs.csv, which the README
// and docs/results.md quote) in every column but the run id and step times.
// Release only (a ...AtScale suite, see the Makefile): the committed file was
// written by the Release build, and other compilers may round differently.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>

#include "sweep/summaries_csv.hpp"
#include "sweep/sweep_runner.hpp"
#include "sweep_test_support.hpp"

namespace rrlab::sweep {
namespace {

std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char ch = line[i];
    if (quoted) {
      if (ch == '"' && i + 1 < line.size() && line[i + 1] == '"') field += '"', ++i;
      else if (ch == '"') quoted = false;
      else field += ch;
    } else if (ch == '"') {
      quoted = true;
    } else if (ch == ',') {
      fields.push_back(field);
      field.clear();
    } else {
      field += ch;
    }
  }
  fields.push_back(field);
  return fields;
}

// key -> column -> value, without the run id and the step times.
std::map<std::string, std::map<std::string, std::string>> deterministic_rows(std::istream& in) {
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = csv_fields(line);
  std::map<std::string, std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    const std::vector<std::string> fields = csv_fields(line);
    std::map<std::string, std::string> row;
    for (size_t i = 0; i < header.size() && i < fields.size(); ++i)
      if (header[i] != "run" && header[i].rfind("step_us", 0) != 0) row[header[i]] = fields[i];
    rows[row["key"]] = row;
  }
  return rows;
}

TEST(CommittedBenchmarkAtScale, ASliceOfTheDefaultSuiteMatchesTheCommittedRuns) {
  nlohmann::json spec_json = nlohmann::json::parse(std::ifstream(testing::source_dir() / "benchmarks/default.json"));
  for (nlohmann::json& entry : spec_json["scenarios"]) entry["count"] = 2;
  const SweepSpec spec = testing::parse_spec(spec_json);
  const std::vector<SweepCase> cases = expand_sweep(spec);
  testing::TempDir dir;
  storage::RunStore store(dir.file("slice.db"));
  RunnerOptions options;
  options.jobs = 2;
  ASSERT_EQ(run_sweep(spec, cases, store, options).stored, cases.size());
  std::stringstream rerun;
  write_summaries_csv(rerun, cases, store.sweep_runs(spec.name));

  std::ifstream committed_file(testing::source_dir() / "benchmarks/default-runs.csv");
  ASSERT_TRUE(committed_file);
  const auto committed = deterministic_rows(committed_file);
  const auto now = deterministic_rows(rerun);
  ASSERT_EQ(now.size(), cases.size());
  for (const auto& [key, row] : now) {
    const auto it = committed.find(key);
    ASSERT_NE(it, committed.end()) << key << " is not in benchmarks/default-runs.csv";
    for (const auto& [column, value] : row)
      EXPECT_EQ(it->second.at(column), value) << key << " " << column
                                              << ": the committed benchmark no longer matches the code; re-run it "
                                                 "(docs/results.md, Benchmark)";
  }
}

}  // namespace
}  // namespace rrlab::sweep
