#include <rrlab/server/app/run_record_json.hpp>
#include <rrlab/server/routes/routes.hpp>
#include <rrlab/scenario/json_reader.hpp>
#include <rrlab/storage/run_store.hpp>
#include <rrlab/util/nesting_depth.hpp>

namespace rrlab::server {

using nlohmann::json;

namespace {

json events_json(storage::RunStore& store, std::int64_t run) {
  json list = json::array();
  for (const storage::StoredEvent& e : store.events(run))
    list.push_back({{"seq", e.seq}, {"step", e.step}, {"kind", e.kind}, {"payload", parse_json(e.payload_json)}});
  return list;
}

// Method and parameters of a request ("method", "params") applied to a scenario.
void apply_method_choice(JsonObject& body, const json& doc, Scenario& scenario) {
  if (body.has("method")) {
    const std::string method = body.string("method");
    require_method(method, "method");
    if (method != scenario.method.name) {
      scenario.method.name = method;
      scenario.method.params.clear();  // the scenario's parameters belong to its own method
    }
  }
  if (body.has("params")) {
    const auto params = resolve_method_params(scenario.method.name, doc.at("params"), "params");
    scenario.method.params.insert(scenario.method.params.end(), params.begin(), params.end());
  }
}

}  // namespace

storage::RunRecord find_run(RouteContext& c, std::int64_t id) {
  auto run = c.runs.store().run(id);
  if (!run) throw DomainError(Problem::not_found, "not_found", "no run " + std::to_string(id), "id");
  return *run;
}

std::shared_ptr<RunGroup> live_group(RouteContext& c, std::int64_t id, int& lane) {
  auto group = c.runs.group_of(id, lane);
  if (!group) {
    find_run(c, id);  // 404 when unknown
    throw DomainError(Problem::conflict, "wrong_state", "run " + std::to_string(id) + " is not running in this server",
                      "id");
  }
  return group;
}

void parse_run_options(JsonObject& body, const json& doc, RunMode default_mode, GroupOptions& options, bool& wait) {
  options.mode = parse_run_mode(body.choice("mode", {"live", "batch"}, to_string(default_mode))).value();
  options.rate = body.number("rate", options.mode == RunMode::batch ? 0.0 : 1.0);
  if (!valid_rate(options.rate)) throw ScenarioError("rate", kRateRule);
  if (options.mode == RunMode::batch) options.rate = 0;
  if (body.has("paused")) {
    if (!doc.at("paused").is_boolean()) throw ScenarioError("paused", "must be true or false");
    options.paused = doc.at("paused").get<bool>() && options.mode == RunMode::live;
  }
  if (body.has("wait")) {
    if (!doc.at("wait").is_boolean()) throw ScenarioError("wait", "must be true or false");
    wait = doc.at("wait").get<bool>();
  }
  if (auto steps = body.optional_number("steps")) {
    if (!(*steps >= 1 && *steps <= double(ScenarioLimits::max_steps)) || *steps != double(long(*steps)))
      throw ScenarioError("steps", "must be an integer in [1, " + std::to_string(ScenarioLimits::max_steps) + "]");
    options.steps = long(*steps);
  }
}

std::int64_t query_int(const RouteContext& c, const std::string& name, std::int64_t def, std::int64_t min,
                       std::int64_t max) {
  auto it = c.request.query.find(name);
  if (it == c.request.query.end()) return def;
  try {
    size_t used = 0;
    const long long v = std::stoll(it->second, &used);
    if (used == it->second.size() && v >= min && v <= max) return v;
  } catch (const std::exception&) {
  }
  throw DomainError(Problem::invalid, "invalid",
                    "must be an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]", name);
}

Scenario resolve_scenario(RouteContext& c, const json& value, const std::string& path) {
  json doc;
  if (value.is_string()) {
    try {
      doc = c.runs.catalogue().document(value.get<std::string>());
    } catch (const DomainError& e) {
      throw DomainError(Problem::not_found, "not_found", e.what(), path);
    }
  } else if (value.is_object()) {
    doc = value;
  } else {
    throw DomainError(Problem::invalid, "invalid", "must be a scenario name or a scenario object", path);
  }
  try {
    return parse_scenario(doc);
  } catch (...) {
    rethrow_as_domain_error(path, Problem::unprocessable);
  }
}

ApiResponse post_run(RouteContext& c) {
  const json doc = parse_body(c.request);
  if (!doc.is_object()) throw DomainError(Problem::invalid, "invalid", "the body must be a JSON object");
  GroupOptions options;
  Scenario scenario;
  bool wait = true;
  try {
    JsonObject body(doc, "");
    body.check_keys({"scenario", "method", "params", "mode", "rate", "paused", "steps", "wait", "display_hz"});
    if (!body.has("scenario")) throw ScenarioError("scenario", "is required (a scenario name or object)");
    scenario = resolve_scenario(c, doc.at("scenario"), "scenario");
    apply_method_choice(body, doc, scenario);
    parse_run_options(body, doc, RunMode::live, options, wait);
    options.display_hz = body.number("display_hz", c.runs.limits().default_display_hz);
    if (!(options.display_hz >= 1 && options.display_hz <= 240)) throw ScenarioError("display_hz", "must be in [1, 240]");
  } catch (...) {
    rethrow_as_domain_error("");
  }
  options.owner = c.request.address;  // live runs are counted per address
  auto group = c.runs.start_group({scenario}, options);
  const std::int64_t id = group->run_id(0);
  if (options.mode == RunMode::batch && wait) {
    ApiResponse response;
    response.deferred = [group](Responder respond) {
      group->when_finished([group, respond] {
        json body = group->status_json(0);
        body["summary"] = group->summary_json(0);
        respond(json_response(200, body));
      });
    };
    return response;
  }
  json body = group->status_json(0);
  body["ws"] = "/ws/runs/" + std::to_string(id);
  return json_response(201, body);
}

ApiResponse list_runs(RouteContext& c) {
  storage::RunFilter filter;
  const auto& q = c.request.query;
  if (auto it = q.find("scenario"); it != q.end()) filter.scenario = it->second;
  if (auto it = q.find("method"); it != q.end()) filter.method = it->second;
  if (auto it = q.find("status"); it != q.end()) filter.status = it->second;
  // ?sweep=NAME: that sweep's runs; ?sweep=none: runs of no sweep
  if (auto it = q.find("sweep"); it != q.end()) filter.sweep = it->second == "none" ? "" : it->second;
  filter.limit = int(query_int(c, "limit", 100, 1, 1000));
  filter.offset = int(query_int(c, "offset", 0, 0, 1'000'000'000));
  json list = json::array();
  for (const storage::RunRecord& r : c.runs.store().runs(filter)) list.push_back(run_record_json(r));
  return json_response(200, list);
}

ApiResponse get_run(RouteContext& c) {
  const std::int64_t id = c.id();
  // The group's state first, the stored row after: a group seen finished has
  // stored its summary by then (read the other way round, a run that ended in
  // between showed "failed" with the summary of the row read while it ran).
  int lane = 0;
  const auto group = c.runs.group_of(id, lane);
  const bool finished = group && group->finished();
  json live, summary;
  if (group) {
    live = group->status_json(lane);
    if (!finished) summary = group->summary_json(lane);
  }
  json body = run_record_json(find_run(c, id));
  if (group) {
    body["live"] = live;
    body["status"] = live["status"];
    if (!finished) body["summary"] = summary;
  }
  return json_response(200, body);
}

// 200 {"deleted": id}; 404 unknown; 409 while live, replayed or re-simulated (RunManager::delete_run).
ApiResponse delete_run(RouteContext& c) { return json_response(200, c.runs.delete_run(c.id())); }

ApiResponse get_run_events(RouteContext& c) {
  const std::int64_t id = c.id();
  find_run(c, id);
  return json_response(200, events_json(c.runs.store(), id));
}

// The run as a record `rrlab run` takes back (sim/run_record.hpp).
ApiResponse get_run_record(RouteContext& c) {
  const storage::RunRecord run = find_run(c, c.id());
  json scenario = parse_json(run.scenario_json);
  scenario["method"] = {{"name", run.method}, {"params", parse_json(run.params_json)}};
  scenario["seed"] = run.seed;
  return json_response(200, {{"rrlab_record", 1},
                             {"run", run.id},
                             {"scenario", scenario},
                             {"frames", run.frames},
                             {"events", events_json(c.runs.store(), run.id)}});
}

}  // namespace rrlab::server
