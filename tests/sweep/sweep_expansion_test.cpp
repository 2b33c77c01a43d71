// Expansion: the fixed order, the keys, shards that partition it.
#include <gtest/gtest.h>

#include <set>

#include <rrlab/generators/generators.hpp>
#include <rrlab/sweep/sweep_expansion.hpp>

#include "sweep_test_support.hpp"

namespace rrlab::sweep {
namespace {

using testing::parse_spec;
using testing::small_spec;

TEST(SweepExpansion, ScenarioThenCaseThenConfigThenSeed) {
  const std::vector<SweepCase> cases = expand_sweep(parse_spec(small_spec()));
  ASSERT_EQ(cases.size(), 2u * 3u * 2u);
  EXPECT_EQ(cases[0].key, "small/file:01_planar7_obstacles/pinv/1");
  EXPECT_EQ(cases[1].key, "small/file:01_planar7_obstacles/pinv/2");
  EXPECT_EQ(cases[2].key, "small/file:01_planar7_obstacles/dls{lambda=0.02}/1");
  EXPECT_EQ(cases[5].key, "small/file:01_planar7_obstacles/dls{lambda=0.10000000000000001}/2");
  EXPECT_EQ(cases[6].key, "small/file:11_sezgin_ex1_box/pinv/1");
  std::set<std::string> keys;
  for (size_t i = 0; i < cases.size(); ++i) {
    EXPECT_EQ(cases[i].position, i);
    EXPECT_EQ(cases[i].family, "file");
    keys.insert(cases[i].key);
  }
  EXPECT_EQ(keys.size(), cases.size());
}

TEST(SweepExpansion, WithoutSeedsEachScenarioKeepsItsOwn) {
  nlohmann::json doc = small_spec();
  doc.erase("seeds");
  const std::vector<SweepCase> cases = expand_sweep(parse_spec(doc));
  ASSERT_EQ(cases.size(), 6u);
  EXPECT_EQ(cases[0].key, "small/file:01_planar7_obstacles/pinv/own");
  EXPECT_FALSE(cases[0].seed);
}

TEST(SweepExpansion, SameSpecSameRunsSameOrder) {
  const std::vector<SweepCase> a = expand_sweep(parse_spec(small_spec()));
  const std::vector<SweepCase> b = expand_sweep(parse_spec(small_spec()));
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].key, b[i].key);
}

TEST(SweepExpansion, ShardsPartitionTheExpansionByPosition) {
  const std::vector<SweepCase> all = expand_sweep(parse_spec(small_spec()));
  std::multiset<std::string> union_keys;
  for (int i = 0; i < 4; ++i) {
    const std::vector<SweepCase> shard = cases_of_shard(all, {i, 4});
    for (size_t k = 0; k < shard.size(); ++k) {
      EXPECT_EQ(shard[k].position % 4, size_t(i));
      if (k) EXPECT_LT(shard[k - 1].position, shard[k].position);
      union_keys.insert(shard[k].key);
    }
  }
  ASSERT_EQ(union_keys.size(), all.size());
  for (const SweepCase& c : all) EXPECT_EQ(union_keys.count(c.key), 1u) << c.key;
}

// A generator entry expands to `count` cases named gen:FAMILY:SEED:INDEX.
// Built without parsing, so it holds with the generator stub too.
TEST(SweepExpansion, GeneratorEntryExpandsToCountCasesByName) {
  SweepSpec spec = parse_spec(small_spec("gen"));
  ScenarioEntry entry;
  entry.family = "planar_clutter";
  entry.name = "planar_clutter";
  entry.seed = 7;
  entry.count = 5;
  spec.scenarios = {entry};
  spec.seeds.clear();
  const std::vector<SweepCase> cases = expand_sweep(spec);
  ASSERT_EQ(cases.size(), 5u * 3u);
  for (int i = 0; i < 5; ++i) {
    const SweepCase& c = cases[size_t(i) * 3];
    EXPECT_EQ(c.scenario_key, "gen:planar_clutter:7:" + std::to_string(i));
    EXPECT_EQ(c.key, "gen/gen:planar_clutter:7:" + std::to_string(i) + "/pinv/own");
    EXPECT_EQ(c.family, "planar_clutter");
    EXPECT_EQ(c.index, i);
  }
}

TEST(SweepExpansion, ParsedGeneratorEntryRunsItsCases) {
  nlohmann::json doc = small_spec("gen");
  doc["scenarios"] = nlohmann::json::parse(R"([{"generator": "planar_clutter", "count": 3, "seed": 11}])");
  doc.erase("seeds");
  const SweepSpec spec = parse_spec(doc);
  const std::vector<SweepCase> cases = expand_sweep(spec);
  ASSERT_EQ(cases.size(), 3u * 3u);
  EXPECT_EQ(cases.back().scenario_key, "gen:planar_clutter:11:2");
  // the generated scenarios are what the cases run: the same document each time
  EXPECT_EQ(generate_scenario("planar_clutter", nlohmann::json::object(), 11, 2),
            generate_scenario("planar_clutter", nlohmann::json::object(), 11, 2));
}

// The size POST /api/sweeps checks before expanding (a short spec of many
// large generator entries took seconds and gigabytes to expand, then was refused).
TEST(SweepExpansion, CaseCountIsTheExpansionsSizeWithoutExpanding) {
  const SweepSpec small = parse_spec(small_spec());
  EXPECT_EQ(sweep_case_count(small), expand_sweep(small).size());  // 2 x 3 x 2 = 12
  nlohmann::json doc = small_spec("gen");
  doc["scenarios"] = nlohmann::json::parse(R"([{"generator": "planar_clutter", "count": 3, "seed": 11}, "01_planar7_obstacles"])");
  doc.erase("seeds");
  const SweepSpec generated = parse_spec(doc);
  EXPECT_EQ(sweep_case_count(generated), expand_sweep(generated).size());  // (3 + 1) x 3 = 12
  doc["scenarios"] = nlohmann::json::array();
  for (int i = 0; i < 50; ++i) doc["scenarios"].push_back({{"generator", "planar_clutter"}, {"count", 1000000}, {"seed", i}});
  doc["seeds"] = nlohmann::json::array({1, 2});
  EXPECT_EQ(sweep_case_count(parse_spec(doc)), 50u * 1000000u * 3u * 2u);
}

}  // namespace
}  // namespace rrlab::sweep
