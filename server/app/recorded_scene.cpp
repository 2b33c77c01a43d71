#include <rrlab/server/app/recorded_scene.hpp>

#include <optional>

#include <rrlab/sim/run_inputs.hpp>
#include <rrlab/storage/resimulation.hpp>
#include <rrlab/util/nesting_depth.hpp>

namespace rrlab::server {

RecordedScene::RecordedScene(const storage::RunRecord& run, std::vector<storage::StoredEvent> events)
    : scenario_(storage::scenario_of_run(run)), sim_(std::make_unique<Simulator>(scenario_)) {
  for (storage::StoredEvent& e : events) {
    const std::optional<InputKind> kind = parse_input_kind(e.kind);
    if (kind && *kind != InputKind::params && *kind != InputKind::joystick) events_.push_back(std::move(e));
  }
}

bool RecordedScene::seek(std::int64_t seq) {
  bool changed = false;
  if (seq < at_) {
    sim_ = std::make_unique<Simulator>(scenario_);
    next_event_ = 0;
    ++version_;
    changed = true;
  }
  at_ = seq;
  while (next_event_ < events_.size() && events_[next_event_].seq <= seq) {
    const storage::StoredEvent& e = events_[next_event_++];
    try {
      apply_input(*sim_, e.kind, parse_json(e.payload_json));
      ++version_;
      changed = true;
    } catch (const std::exception&) {
      // an input the run refused when it was recorded changes nothing now either
    }
  }
  return changed;
}

}  // namespace rrlab::server
