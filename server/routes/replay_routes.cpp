// Replay: stream a run's stored frames (mode "frames", to /ws/replays/{id})
// or re-simulate it from its recorded events into a new run and compare every
// frame byte for byte (mode "resimulate").
#include <algorithm>
#include <thread>

#include <rrlab/scenario/json_reader.hpp>
#include <rrlab/server/app/replay_player.hpp>
#include <rrlab/server/routes/routes.hpp>
#include <rrlab/storage/frame_codec.hpp>
#include <rrlab/storage/frame_writer.hpp>
#include <rrlab/storage/resimulation.hpp>
#include <rrlab/storage/run_store.hpp>

namespace rrlab::server {

using nlohmann::json;

namespace {

ApiResponse resimulate_run(RouteContext& c, const storage::RunRecord& run) {
  RunManager& runs = c.runs;
  // a re-simulation stores a copy of the run's frames: admitted like a run of as many steps
  std::int64_t reserved = 0;
  try {
    std::int64_t frames = run.frames;
    std::int64_t frame_bytes = run.frames > 0 ? (run.frame_bytes + run.frames - 1) / run.frames : 0;
    const Scenario scenario = storage::scenario_of_run(run);
    if (frames == 0) {
      // a run that stored no frames is stepped as far as its summary says: admitted for that many,
      // each the size of its first frame packed (as a new run is)
      frames = storage::summary_steps(run);
      const Simulator sim(scenario);
      frame_bytes = std::int64_t(storage::pack_frame(sim.frame()).size());
    }
    reserved = runs.admit_work({estimate_lane(scenario, frames, frame_bytes)}, true);
  } catch (const DomainError&) {
    throw;
  } catch (...) {
    rethrow_as_domain_error("", Problem::unprocessable);  // a stored scenario this rrlab can no longer build
  }
  try {
    runs.begin_job(run.id);  // 503 when too many runs are active
  } catch (...) {
    runs.release_reserved(reserved);
    throw;
  }
  ApiResponse response;
  response.deferred = [&runs, run, reserved](Responder respond) {
    const auto job = [&runs, run, respond, reserved]() mutable {  // reserved: what is left of the reservation
      std::int64_t id = 0;
      try {
        storage::NewRun fresh;
        fresh.scenario_name = run.scenario_name;
        fresh.scenario_json = run.scenario_json;
        fresh.method = run.method;
        fresh.params_json = run.params_json;
        fresh.mode = to_string(RunMode::resimulation);
        fresh.seed = run.seed;
        fresh.dof = run.dof;
        fresh.diagnostic_names_json = run.diagnostic_names_json;
        fresh.source_run = run.id;
        id = runs.store().create_run(fresh);
        for (const storage::StoredEvent& e : runs.store().events(run.id)) runs.store().add_event(id, e);
        const storage::ResimulationResult result =
            storage::resimulate(runs.store(), run, [&](std::int64_t seq, const Frame& f, const std::string& packed) {
              if (runs.stopping()) throw std::runtime_error("the server is stopping");
              runs.writer().push(id, storage::stored_frame(seq, f, packed));
              // a pushed frame counts as stored: its share of the reservation goes (as a run's does)
              const std::int64_t used = std::min<std::int64_t>(reserved, std::int64_t(packed.size()));
              runs.release_reserved(used);
              reserved -= used;
            });
        runs.writer().flush();
        json summary = summary_to_json(result.summary);
        summary["run"] = id;
        json verification = {{"run", id}, {"source_run", run.id}};
        verification.update(storage::verification_json(result));
        summary["verification"] = verification;
        runs.store().finish_run(id, to_string(RunStatus::completed), summary.dump());
        runs.done_reading(run.id);  // before the answer: its client may delete the run at once
        respond(json_response(200, verification));
      } catch (const std::exception& e) {
        if (id != 0) {
          try {
            runs.writer().flush();
            runs.store().finish_run(id, to_string(RunStatus::failed), safe_dump({{"failure", e.what()}}));
          } catch (const std::exception&) {
          }
        }
        runs.done_reading(run.id);
        respond(error_response(DomainError(Problem::internal, "resimulation_failed", e.what())));
      }
      // released before end_job: it owns the HTTP session, which must be gone
      // before stop_all() returns and the server destroys its I/O context (ASan
      // caught the session's socket closed through the freed context at shutdown)
      respond = nullptr;
      runs.release_reserved(reserved);  // what its frames did not use (or all of it when it failed)
      runs.end_job();
    };
    try {
      std::thread(job).detach();
    } catch (const std::exception& e) {
      runs.done_reading(run.id);
      runs.release_reserved(reserved);
      runs.end_job();
      respond(error_response(DomainError(Problem::busy, "busy", std::string("cannot start a thread: ") + e.what())));
    }
  };
  return response;
}

}  // namespace

ApiResponse post_replay(RouteContext& c) {
  const storage::RunRecord run = find_run(c, c.id());
  const json doc = c.request.body.empty() ? json::object() : parse_body(c.request);
  std::string mode;
  double speed = 1.0;
  std::int64_t from = 0;
  try {
    JsonObject body(doc, "");
    body.check_keys({"mode", "speed", "from"});
    mode = body.choice("mode", {"frames", "resimulate"}, "frames");
    speed = body.number("speed", 1.0);
    if (!(speed > 0 && speed <= 1000)) throw ScenarioError("speed", "must be in (0, 1000]");
    const double first = body.number("from", 0);
    if (!(first >= 0 && first < 1e15)) throw ScenarioError("from", "must be a frame number");
    from = std::int64_t(first);
  } catch (...) {
    rethrow_as_domain_error("");
  }
  int lane = 0;
  auto group = c.runs.group_of(run.id, lane);
  if (group && !group->finished())
    throw DomainError(Problem::conflict, "wrong_state",
                      "run " + std::to_string(run.id) + " is still running; stop it first", "id");
  if (mode == "resimulate") return resimulate_run(c, run);
  auto player = std::make_shared<ReplayPlayer>(c.runs.store(), run, speed, from, c.runs.limits().default_display_hz);
  c.runs.add_replay(player, c.request.owner());
  player->start();
  return json_response(201, player->status());
}

ApiResponse get_replay(RouteContext& c) {
  auto player = c.runs.replay(c.id());
  if (!player) throw DomainError(Problem::not_found, "not_found", "no replay " + c.captures.at(0), "id");
  return json_response(200, player->status());
}

ReplayCommand parse_replay_command(const json& body) {
  ReplayCommand command;
  try {
    JsonObject obj(body, "");
    obj.check_keys({"action", "seq", "speed"});
    if (obj.has("action")) command.action = parse_replay_action(obj.choice("action", {"play", "pause", "seek"})).value();
    command.speed = obj.optional_number("speed");
    command.seq = obj.optional_number("seq");
  } catch (...) {
    rethrow_as_domain_error("");
  }
  return command;
}

ApiResponse post_replay_control(RouteContext& c) {
  auto player = c.runs.replay(c.id());
  if (!player) throw DomainError(Problem::not_found, "not_found", "no replay " + c.captures.at(0), "id");
  return json_response(200, player->control(parse_replay_command(parse_body(c.request))));
}

}  // namespace rrlab::server
