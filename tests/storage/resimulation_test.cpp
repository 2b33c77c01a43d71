// Re-simulating a run that stored no frames but completed steps (a sweep's
// run): the engine steps as far as its summary says, hands every frame to the
// caller (the server stores them, so the run can be replayed) and compares the
// summary's result fields bit for bit.
#include <fstream>
#include <sstream>

#include <rrlab/storage/frame_codec.hpp>
#include <rrlab/storage/frame_writer.hpp>
#include <rrlab/storage/resimulation.hpp>

#include "temp_store_test.hpp"

namespace rrlab::storage {
namespace {

using nlohmann::json;

class Resimulation : public TempStoreTest {
 protected:
  // A frameless completed run of 01_planar7_obstacles with dls, `steps` steps.
  std::int64_t store_frameless(RunStore& store, int steps, const std::function<void(json&)>& tamper = {}) {
    std::ifstream in(std::string(RRLAB_SOURCE_DIR) + "/scenarios/01_planar7_obstacles.json");
    std::stringstream text;
    text << in.rdbuf();
    const Scenario scenario = parse_scenario_text(text.str());
    Simulator sim(scenario, "dls");
    sim.set_total_steps(steps);
    json summary = summary_to_json(run_to_end(sim, nullptr));
    if (tamper) tamper(summary);
    const std::int64_t id = store.create_run(new_run_of(scenario, sim, "batch"));
    store.finish_run(id, "completed", summary.dump());
    return id;
  }
};

TEST_F(Resimulation, AFramelessRunIsSteppedAsFarAsItsSummaryAndItsSummaryCompared) {
  RunStore store(path_);
  const std::int64_t id = store_frameless(store, 120);
  std::int64_t frames = 0;
  const ResimulationResult result = resimulate(store, *store.run(id), [&](std::int64_t seq, const Frame&, const std::string&) {
    EXPECT_EQ(seq, frames);
    ++frames;
  });
  EXPECT_EQ(frames, 120);
  EXPECT_TRUE(result.summary_compared);
  EXPECT_TRUE(result.identical()) << result.summary_mismatch;
  const json verdict = verification_json(result);
  EXPECT_EQ(verdict["identical"], true);
  EXPECT_EQ(verdict["compared"], true);
  EXPECT_EQ(verdict["frames_compared"], 0);
  EXPECT_EQ(verdict["summary_compared"], true);
}

TEST_F(Resimulation, ASummaryThatDiffersIsNamed) {
  RunStore store(path_);
  const std::int64_t id = store_frameless(store, 60, [](json& s) { s["min_distance"] = s["min_distance"].get<double>() + 1e-12; });
  const ResimulationResult result = resimulate(store, *store.run(id), {});
  EXPECT_TRUE(result.compared());
  EXPECT_FALSE(result.identical());
  EXPECT_EQ(result.summary_mismatch.rfind("min_distance ", 0), 0u) << result.summary_mismatch;
  EXPECT_EQ(verification_json(result)["mismatch"].get<std::string>().rfind("summary: min_distance", 0), 0u);
}

// A run stored before frame blobs had a version word (version 1) is compared
// in its own format, and matches.
TEST_F(Resimulation, ARunStoredInAnOlderBlobFormatMatchesInThatFormat) {
  RunStore store(path_);
  std::ifstream in(std::string(RRLAB_SOURCE_DIR) + "/scenarios/01_planar7_obstacles.json");
  std::stringstream text;
  text << in.rdbuf();
  const Scenario scenario = parse_scenario_text(text.str());
  Simulator sim(scenario, "dls");
  for (int version = 1; version < kFrameBlobVersion; ++version) {
    Simulator sim(scenario, "dls");
    const std::int64_t id = store.create_run(new_run_of(scenario, sim, "batch"));
    {
      FrameWriter writer(store);
      std::string old;
      for (std::int64_t seq = 0; seq < 50; ++seq) {
        sim.step();
        pack_frame(sim.frame(), old, version);
        writer.push(id, stored_frame(seq, sim.frame(), old));
      }
      writer.flush();
    }
    store.finish_run(id, "completed", summary_to_json(sim.summary()).dump());
    const ResimulationResult result = resimulate(store, *store.run(id), {});
    EXPECT_EQ(result.frames_compared, 50) << "version " << version;
    EXPECT_FALSE(result.first_mismatch) << "version " << version << ": " << result.mismatch;
  }
}

// A run whose arm folds across itself, stored before self-collision (blob
// version 2, summary format 1 with `collided` false): it still verifies.
TEST_F(Resimulation, ASelfCollidingRunStoredBeforeSelfCollisionStillVerifies) {
  RunStore store(path_);
  const Scenario scenario = parse_scenario_text(R"({
    "name": "folded", "dt": 0.01, "duration": 0.3, "angle_unit": "deg",
    "robot": {"kind": "planar", "links": [{"length": 1, "radius": 0.05}, {"length": 1, "radius": 0.05},
                                          {"length": 1, "radius": 0.05}],
              "q0": [0, 150, 150]},
    "task": {"space": "xy", "trajectory": {"type": "polyline", "points": [[0.6, -0.4], [0.7, -0.4]]}},
    "method": {"name": "dls"}})");
  Simulator sim(scenario);
  const std::int64_t id = store.create_run(new_run_of(scenario, sim, "batch"));
  {
    FrameWriter writer(store);
    std::string v2;
    for (std::int64_t seq = 0; seq < 30; ++seq) {
      sim.step();
      pack_frame(sim.frame(), v2, 2);
      writer.push(id, stored_frame(seq, sim.frame(), v2));
    }
    writer.flush();
  }
  const Summary summary = sim.summary();
  ASSERT_TRUE(summary.self_collided);
  json old = summary_to_json(summary);
  for (const char* field : {"format", "obstacle_collided", "self_collided", "min_self_distance", "rms_qddot",
                            "max_qddot", "rms_jerk", "max_jerk"})
    old.erase(field);
  old["collided"] = summary.obstacle_collided;  // what the first format said
  store.finish_run(id, "completed", old.dump());
  const ResimulationResult result = resimulate(store, *store.run(id), {});
  EXPECT_EQ(result.frames_compared, 30);
  EXPECT_TRUE(result.identical()) << result.mismatch << result.summary_mismatch;
}

// A summary stored before self-collision (no "format"): `collided` meant an
// obstacle contact and is compared as such, and the newer fields are not
// compared. A format-2 summary compares them.
TEST_F(Resimulation, ASummaryOfTheFirstFormatIsComparedUnderItsOwnRules) {
  RunStore store(path_);
  const std::int64_t old = store_frameless(store, 40, [](json& s) {
    s.erase("format");
    s.erase("obstacle_collided");
    s.erase("self_collided");
    s.erase("min_self_distance");
    for (const char* field : {"rms_qddot", "max_qddot", "rms_jerk", "max_jerk"}) s.erase(field);
  });
  const ResimulationResult result = resimulate(store, *store.run(old), {});
  EXPECT_TRUE(result.identical()) << result.summary_mismatch;

  for (const char* field : {"self_collided", "rms_jerk"}) {
    const std::int64_t changed = store_frameless(store, 40, [&](json& s) { s[field] = 1; });
    const ResimulationResult fresh = resimulate(store, *store.run(changed), {});
    EXPECT_FALSE(fresh.identical());
    EXPECT_EQ(fresh.summary_mismatch.rfind(std::string(field) + " ", 0), 0u) << fresh.summary_mismatch;
  }
}

TEST_F(Resimulation, ASummaryOfTheSecondFormatSkipsOnlyTheLimitStepCounts) {
  RunStore store(path_);
  const std::int64_t old = store_frameless(store, 40, [](json& s) {
    s["format"] = 2;
    s.erase("position_limit_steps");
    s.erase("velocity_limit_steps");
  });
  const ResimulationResult result = resimulate(store, *store.run(old), {});
  EXPECT_TRUE(result.identical()) << result.summary_mismatch;

  // format 3 compares them, format 2 still compares what it had
  const std::int64_t changed = store_frameless(store, 40, [](json& s) { s["position_limit_steps"] = 7; });
  EXPECT_EQ(resimulate(store, *store.run(changed), {}).summary_mismatch.rfind("position_limit_steps ", 0), 0u);
  const std::int64_t jerk = store_frameless(store, 40, [](json& s) {
    s["format"] = 2;
    s.erase("position_limit_steps");
    s["rms_jerk"] = 1;
  });
  EXPECT_EQ(resimulate(store, *store.run(jerk), {}).summary_mismatch.rfind("rms_jerk ", 0), 0u);
}

TEST_F(Resimulation, ARunWithNeitherFramesNorStepsHasNothingToCompare) {
  RunStore store(path_);
  const std::int64_t id = store.create_run(new_run());
  store.finish_run(id, "stopped", json{{"steps", 0}}.dump());
  // its scenario "{}" cannot even be built: the stored run is refused, not stepped
  EXPECT_ANY_THROW(resimulate(store, *store.run(id), {}));
}

}  // namespace
}  // namespace rrlab::storage
