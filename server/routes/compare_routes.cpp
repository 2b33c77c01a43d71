// Several methods on one scenario in lockstep: the same steps, and the same
// scene, joystick and reset inputs applied to every lane.
#include <rrlab/scenario/json_reader.hpp>
#include <rrlab/server/routes/routes.hpp>

namespace rrlab::server {

using nlohmann::json;

namespace {

// Per-method rows of the metrics people compare, from each lane's summary.
json comparison(RunGroup& group) {
  json rows = json::array();
  for (int lane = 0; lane < group.lane_count(); ++lane) {
    const json s = group.summary_json(lane);
    rows.push_back({{"run", group.run_id(lane)},
                    {"method", s.at("method")},
                    {"collided", s.at("collided")},
                    {"min_distance", s.at("min_distance")},
                    {"max_tracking_error", s.at("max_tracking_error")},
                    {"joint_limit_violated", s.at("joint_limit_violated")},
                    {"max_qdot_ratio", s.at("max_qdot_ratio")},
                    {"max_condition_number", s.at("max_condition_number")},
                    {"step_us_mean", s.at("step_us").at("mean")}});
  }
  return rows;
}

}  // namespace

ApiResponse post_compare(RouteContext& c) {
  const json doc = parse_body(c.request);
  if (!doc.is_object()) throw DomainError(Problem::invalid, "invalid", "the body must be a JSON object");
  std::vector<Scenario> lanes;
  GroupOptions options;
  options.compare = true;
  bool wait = true;
  try {
    JsonObject body(doc, "");
    body.check_keys({"scenario", "methods", "mode", "steps", "wait", "rate", "paused"});
    if (!body.has("scenario")) throw ScenarioError("scenario", "is required (a scenario name or object)");
    const Scenario base = resolve_scenario(c, doc.at("scenario"), "scenario");
    const json& methods = body.array("methods", 8);
    if (methods.size() < 2) throw ScenarioError("methods", "compare needs 2 to 8 methods");
    for (size_t i = 0; i < methods.size(); ++i) {
      const std::string path = index_path("methods", i);
      Scenario lane = base;
      lane.method.params.clear();
      if (methods[i].is_string()) {
        lane.method.name = methods[i].get<std::string>();
        require_method(lane.method.name, path);
      } else {
        JsonObject m(methods[i], path);
        m.check_keys({"name", "params"});
        lane.method.name = m.string("name");
        require_method(lane.method.name, m.child("name"));
        if (m.has("params"))
          lane.method.params = resolve_method_params(lane.method.name, methods[i]["params"], m.child("params"));
      }
      if (lane.method.name == base.method.name && methods[i].is_string()) lane.method.params = base.method.params;
      lanes.push_back(std::move(lane));
    }
    parse_run_options(body, doc, RunMode::batch, options, wait);
  } catch (...) {
    rethrow_as_domain_error("");
  }
  options.owner = c.request.address;  // live runs are counted per address
  auto group = c.runs.start_group(lanes, options);
  json runs = json::array();
  for (int lane = 0; lane < group->lane_count(); ++lane)
    runs.push_back({{"id", group->run_id(lane)},
                    {"method", lanes[size_t(lane)].method.name},
                    {"ws", "/ws/runs/" + std::to_string(group->run_id(lane))}});
  const json head = {{"group", group->run_id(0)}, {"runs", runs}};
  if (options.mode == RunMode::batch && wait) {
    ApiResponse response;
    response.deferred = [group, head](Responder respond) {
      group->when_finished([group, head, respond] {
        json body = head;
        body["comparison"] = comparison(*group);
        respond(json_response(200, body));
      });
    };
    return response;
  }
  return json_response(201, head);
}

}  // namespace rrlab::server
