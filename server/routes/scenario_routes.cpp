#include <rrlab/server/routes/routes.hpp>

namespace rrlab::server {

// {"scenarios": [summary...], "total", "offset", "limit"}: summaries, not the
// scenarios (GET /api/scenarios/{name} has one whole), a page at a time.
ApiResponse list_scenarios(RouteContext& c) {
  const std::int64_t limit = query_int(c, "limit", 100, 1, 1000);
  const std::int64_t offset = query_int(c, "offset", 0, 0, 1'000'000'000);
  return json_response(200, c.runs.catalogue().list(limit, offset));
}

ApiResponse get_scenario(RouteContext& c) {
  return json_response(200, c.runs.catalogue().document(c.captures.at(0)));
}

// Adds a scenario (validated like a file; stored in the database, never on
// disk) under its "name". An existing name, of a file or of one added
// earlier, is 409: never replaced.
ApiResponse post_scenario(RouteContext& c) {
  const nlohmann::json document = parse_body(c.request);
  if (!document.is_object()) throw DomainError(Problem::invalid, "invalid", "must be a scenario object");
  if (!document.contains("name") || !document["name"].is_string())
    throw DomainError(Problem::invalid, "invalid", "a stored scenario needs a string \"name\"", "name");
  return json_response(201, c.runs.catalogue().add(document["name"].get<std::string>(), document));
}

// Checks a scenario as POST /api/runs would, stores nothing (the dashboard's editor).
ApiResponse validate_scenario(RouteContext& c) {
  return json_response(200, c.runs.catalogue().validate(parse_body(c.request)));
}

// A catalogue scenario's first frame, drawn as a run's stream starts (the
// dashboard's start page): its simulator built as validate builds it, frame 0
// computed, nothing stored.
ApiResponse preview_scenario(RouteContext& c) {
  return json_response(200, c.runs.catalogue().preview(c.captures.at(0)));
}

}  // namespace rrlab::server
