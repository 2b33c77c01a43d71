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

ApiResponse get_sweep(RouteContext& c) { return json_response(200, c.runs.sweeps().status(c.id())); }

ApiResponse post_sweep_control(RouteContext& c) {
  return json_response(200, c.runs.sweeps().control(c.id(), parse_body(c.request)));
}

}  // namespace rrlab::server
