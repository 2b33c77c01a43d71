// A run's record: the scenario it started from (method and parameters
// included) and its input events, as one JSON document that `rrlab run`
// takes back and that re-simulation replays:
//   {"rrlab_record": 1, "run": id, "scenario": {...}, "frames": n,
//    "events": [{"seq", "step", "kind", "payload"}, ...]}
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <rrlab/scenario/scenario.hpp>

namespace rrlab {

class Simulator;

struct RecordedEvent {
  long seq = 0;  // applied before the run's seq-th step
  std::string kind;
  nlohmann::json payload;
};

struct RunRecordDoc {
  Scenario scenario;
  std::vector<RecordedEvent> events;
  long frames = 0;  // steps the recorded run took (0: unknown)
};

bool is_run_record(const nlohmann::json& doc);
// Throws ScenarioError naming the path.
RunRecordDoc parse_run_record(const nlohmann::json& doc);

// Applies recorded events in order as the run reaches their seq.
class EventReplayer {
 public:
  explicit EventReplayer(const std::vector<RecordedEvent>& events) : events_(events) {}
  // Applies every event with seq <= `seq` not applied yet (apply_input).
  void apply_due(Simulator& sim, long seq);

 private:
  const std::vector<RecordedEvent>& events_;
  size_t next_ = 0;
};

}  // namespace rrlab
