// Sweeps over REST: POST /api/sweeps starts one (202), GET /api/sweeps/{id}
// gives its progress and, once ended, its report; POST .../control stops it.
#include "app/sweep_jobs.hpp"
#include "routes/routes.hpp"

namespace rrlab::server {

ApiResponse post_sweep(RouteContext& c) {
  const int jobs = int(query_int(c, "jobs", 1, 1, 256));
  return json_response(202, c.runs.sweeps().start(parse_body(c.request), jobs));
}

ApiResponse list_sweeps(RouteContext& c) { return json_response(200, c.runs.sweeps().list()); }

ApiResponse get_sweep(RouteContext& c) {
  ApiResponse response;
  response.body = c.runs.sweeps().status(c.id());
  return response;
}

// Checks a spec as POST /api/sweeps would and starts nothing (the dashboard's dialog).
ApiResponse validate_sweep(RouteContext& c) { return json_response(200, c.runs.sweeps().validate(parse_body(c.request))); }

// ?family=&config=&outcome=pass|fail&failure_mode=&limit=&offset=
ApiResponse get_sweep_runs(RouteContext& c) {
  SweepJobs::RunQuery query;
  const auto& q = c.request.query;
  const auto text = [&](const char* name) -> std::optional<std::string> {
    auto it = q.find(name);
    return it == q.end() || it->second.empty() ? std::nullopt : std::optional<std::string>(it->second);
  };
  query.family = text("family");
  query.config = text("config");
  query.outcome = text("outcome");
  query.failure_mode = text("failure_mode");
  if (query.outcome && *query.outcome != "pass" && *query.outcome != "fail")
    throw ApiError(400, "invalid", "must be pass or fail", "outcome");
  query.limit = query_int(c, "limit", 100, 1, 1000);
  query.offset = query_int(c, "offset", 0, 0, 1'000'000'000);
  return json_response(200, c.runs.sweeps().runs(c.id(), query));
}

ApiResponse post_sweep_control(RouteContext& c) {
  return json_response(200, c.runs.sweeps().control(c.id(), parse_body(c.request)));
}

}  // namespace rrlab::server
