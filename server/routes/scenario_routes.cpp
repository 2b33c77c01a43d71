#include "routes/routes.hpp"

namespace rrlab::server {

ApiResponse list_scenarios(RouteContext& c) { return json_response(200, c.runs.scenario_list()); }

ApiResponse get_scenario(RouteContext& c) { return json_response(200, c.runs.scenario_json(c.captures.at(0))); }

// Adds a scenario (validated like a file; stored in the database, never on
// disk). An existing name, of a file or of one added earlier, is 409: never replaced.
ApiResponse post_scenario(RouteContext& c) { return json_response(201, c.runs.add_scenario(parse_body(c.request))); }

// Checks a scenario as POST /api/runs would, stores nothing (the dashboard's editor).
ApiResponse validate_scenario(RouteContext& c) {
  return json_response(200, c.runs.validate_scenario(parse_body(c.request)));
}

}  // namespace rrlab::server
