// REST routes, one file per resource; router.cpp holds the table. The
// routes parse requests into the app's typed arguments and answer its
// DomainErrors with the status of their Problem (http_errors.hpp).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>
#include <memory>
#include <string_view>
#include <vector>

#include <rrlab/scenario/json_reader.hpp>
#include <rrlab/server/app/run_record_json.hpp>  // run_record_json
#include <rrlab/server/api/errors.hpp>
#include <rrlab/server/api/request.hpp>
#include <rrlab/server/api/response.hpp>
#include <rrlab/server/app/run_manager.hpp>
#include <rrlab/server/routes/http_errors.hpp>
#include <rrlab/storage/run_store.hpp>

namespace rrlab::server {

struct ServerInfo {
  std::string version;
  std::chrono::steady_clock::time_point started;
  const std::atomic<int>* websockets = nullptr;  // connected WebSocket clients
  const std::atomic<int>* building = nullptr;    // slow requests queued or under way on the worker pool
};

struct RouteContext {
  RunManager& runs;
  const ServerInfo& info;
  const ApiRequest& request;
  std::vector<std::string> captures;  // the {} segments of the route's pattern

  std::int64_t id(size_t index = 0) const;  // a numeric capture (not_found if not a number)
};

using RouteHandler = ApiResponse (*)(RouteContext&);

// Dispatches /api/... requests; unknown paths 404, known paths with another verb 405.
ApiResponse handle_api(RunManager& runs, const ServerInfo& info, const ApiRequest& request);

// The router's table, in dispatch order: verb and pattern ("{}" matches one
// path segment). The OpenAPI test checks the document against it.
struct RouteInfo {
  std::string verb, pattern;
};
// Whether the request's route is slow work (it builds scenarios or their
// summaries, or deletes a run's frames): the network layer then answers it
// from the worker pool, off the I/O threads.
bool is_slow(const ApiRequest& request);
std::vector<RouteInfo> api_routes();

// The WebSocket routes, in the same table as the REST ones: GET /ws/runs/{id}
// streams a live run's lane, /ws/replays/{id} a replay. The frame source the
// path names; not_found (DomainError) when it names none.
std::shared_ptr<FrameSource> websocket_source(RunManager& runs, std::string_view path);
std::vector<RouteInfo> websocket_routes();

// openapi_routes.cpp: GET /api/openapi.json, the OpenAPI 3.1 document of every
// route (server/openapi.json with docs/scenario.schema.json as its Scenario
// schema, both compiled in).
ApiResponse get_openapi(RouteContext&);
const nlohmann::json& openapi_document();

// health_routes.cpp
ApiResponse get_health(RouteContext&);
ApiResponse get_methods(RouteContext&);
// scenario_routes.cpp
ApiResponse list_scenarios(RouteContext&);
ApiResponse get_scenario(RouteContext&);
ApiResponse post_scenario(RouteContext&);
ApiResponse validate_scenario(RouteContext&);
ApiResponse preview_scenario(RouteContext&);
// run_routes.cpp
ApiResponse post_run(RouteContext&);
ApiResponse list_runs(RouteContext&);
ApiResponse get_run(RouteContext&);
ApiResponse delete_run(RouteContext&);
ApiResponse get_run_record(RouteContext&);
ApiResponse get_run_events(RouteContext&);
// run_input_routes.cpp
ApiResponse post_control(RouteContext&);
ApiResponse patch_params(RouteContext&);
ApiResponse put_obstacle(RouteContext&);
ApiResponse post_obstacle(RouteContext&);
ApiResponse delete_obstacle(RouteContext&);
ApiResponse post_joystick(RouteContext&);
ApiResponse post_method(RouteContext&);
// frame_routes.cpp
ApiResponse get_frames(RouteContext&);
ApiResponse get_drawn_frames(RouteContext&);
// The frame field table (sim/frame_fields.hpp): what the page charts and exports.
ApiResponse get_frame_fields(RouteContext&);
// replay_routes.cpp
ApiResponse post_replay(RouteContext&);
ApiResponse get_replay(RouteContext&);
ApiResponse post_replay_control(RouteContext&);
// compare_routes.cpp
ApiResponse post_compare(RouteContext&);
// export_routes.cpp: a run, or a compare group, as one HTML file that replays offline
ApiResponse get_run_export(RouteContext&);
ApiResponse get_group_export(RouteContext&);

// Shared by the run routes: the stored run (404 if unknown) and its live group if any.
storage::RunRecord find_run(RouteContext& context, std::int64_t id);
std::shared_ptr<RunGroup> live_group(RouteContext& context, std::int64_t id, int& lane);
// The run options shared by POST /api/runs and /api/compare: mode, rate,
// paused, wait, steps (ScenarioError naming the field).
void parse_run_options(JsonObject& body, const nlohmann::json& doc, RunMode default_mode, GroupOptions& options,
                       bool& wait);
// A request's "scenario": a catalogue name (not_found) or a scenario object
// (unprocessable naming the path when the engine refuses it).
Scenario resolve_scenario(RouteContext& context, const nlohmann::json& value, const std::string& path);
// A control body {"action"?: start|pause|step|reset|stop, "rate"?: factor}
// (run_input_routes.cpp; invalid naming the field).
ControlCommand parse_control_command(const nlohmann::json& body);
// A replay's control body {"action"?: play|pause|seek, "seq"?: n, "speed"?: x}
// (replay_routes.cpp; invalid naming the field).
ReplayCommand parse_replay_command(const nlohmann::json& body);

// A query parameter as an integer in [min, max] (invalid naming it otherwise).
std::int64_t query_int(const RouteContext& context, const std::string& name, std::int64_t def, std::int64_t min,
                       std::int64_t max);

// sweep_routes.cpp
ApiResponse post_sweep(RouteContext&);
ApiResponse list_sweeps(RouteContext&);
ApiResponse get_sweep(RouteContext&);
ApiResponse get_sweep_runs(RouteContext&);
ApiResponse validate_sweep(RouteContext&);
ApiResponse post_sweep_control(RouteContext&);

}  // namespace rrlab::server
