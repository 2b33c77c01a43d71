#include <rrlab/sim/run_record.hpp>

#include <rrlab/scenario/json_reader.hpp>
#include <rrlab/sim/run_inputs.hpp>

namespace rrlab {

bool is_run_record(const nlohmann::json& doc) { return doc.is_object() && doc.contains("rrlab_record"); }

RunRecordDoc parse_run_record(const nlohmann::json& doc) {
  JsonObject root(doc, "");
  root.check_keys({"rrlab_record", "run", "scenario", "frames", "events"});
  if (root.number("rrlab_record") != 1) throw ScenarioError("rrlab_record", "only version 1 is known");
  RunRecordDoc record;
  try {
    record.scenario = parse_scenario(root.raw("scenario"));
  } catch (const ScenarioError& e) {
    throw ScenarioError("scenario" + (e.path().empty() ? "" : "." + e.path()), e.what());
  }
  const double frames = root.number("frames", 0);
  if (!(frames >= 0 && frames <= double(ScenarioLimits::max_steps)))
    throw ScenarioError("frames", "must be in [0, " + std::to_string(ScenarioLimits::max_steps) + "]");
  record.frames = long(frames);
  if (root.has("events")) {
    const nlohmann::json& events = root.array("events", 10'000'000);
    long last_seq = 0;
    for (size_t i = 0; i < events.size(); ++i) {
      JsonObject e(events[i], index_path("events", i));
      e.check_keys({"seq", "step", "kind", "payload"});
      RecordedEvent event;
      const double seq = e.number("seq");
      if (!(seq >= 0 && seq <= 1e15) || seq != double(long(seq)) || long(seq) < last_seq)
        throw ScenarioError(e.child("seq"), "must be a non-negative integer, not below the previous event's");
      event.seq = last_seq = long(seq);
      event.kind = e.string("kind");
      event.payload = e.has("payload") ? e.raw("payload") : nlohmann::json::object();
      record.events.push_back(std::move(event));
    }
  }
  return record;
}

void EventReplayer::apply_due(Simulator& sim, long seq) {
  while (next_ < events_.size() && events_[next_].seq <= seq) {
    const RecordedEvent& e = events_[next_];
    try {
      apply_input(sim, e.kind, e.payload);
    } catch (const ScenarioError& error) {
      throw ScenarioError("events[" + std::to_string(next_) + "].payload" +
                              (error.path().empty() ? "" : "." + error.path()),
                          error.what());
    } catch (const InputStateError& error) {
      throw ScenarioError("events[" + std::to_string(next_) + "]", error.what());
    }
    ++next_;
  }
}

}  // namespace rrlab
