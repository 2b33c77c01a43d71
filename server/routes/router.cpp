#include <string_view>

#include <rrlab/server/app/replay_player.hpp>
#include <rrlab/server/routes/routes.hpp>
#include <rrlab/storage/run_store.hpp>

namespace rrlab::server {

namespace {

struct Route {
  const char* verb;
  const char* pattern;  // "{}" matches one path segment
  RouteHandler handler;
  // Slow work: builds scenarios (parsing, URDF and mesh files, simulators) or
  // their summaries, or deletes a run's frames: handled on the worker pool,
  // never on an I/O thread.
  bool slow = false;
};

constexpr Route kRoutes[] = {
    {"GET", "/api/health", get_health},
    {"GET", "/api/methods", get_methods},
    {"GET", "/api/openapi.json", get_openapi},
    {"GET", "/api/frame-fields", get_frame_fields},
    {"GET", "/api/scenarios", list_scenarios, true},
    {"POST", "/api/scenarios", post_scenario, true},
    {"POST", "/api/scenarios/validate", validate_scenario, true},  // the literal before the {} pattern
    {"GET", "/api/scenarios/{}", get_scenario},
    {"GET", "/api/scenarios/{}/preview", preview_scenario, true},  // builds the scenario's simulator
    {"POST", "/api/runs", post_run, true},
    {"GET", "/api/runs", list_runs},
    {"GET", "/api/runs/{}", get_run},
    {"DELETE", "/api/runs/{}", delete_run, true},
    {"GET", "/api/runs/{}/record", get_run_record},
    {"GET", "/api/runs/{}/events", get_run_events},
    {"POST", "/api/runs/{}/control", post_control},
    {"PATCH", "/api/runs/{}/params", patch_params},
    {"POST", "/api/runs/{}/obstacles", post_obstacle, true},
    {"PUT", "/api/runs/{}/obstacles/{}", put_obstacle, true},
    {"DELETE", "/api/runs/{}/obstacles/{}", delete_obstacle},
    {"POST", "/api/runs/{}/joystick", post_joystick},
    {"POST", "/api/runs/{}/method", post_method},
    {"GET", "/api/runs/{}/frames", get_frames},
    {"GET", "/api/runs/{}/drawn", get_drawn_frames, true},  // loads the run's scenario
    {"GET", "/api/runs/{}/export.html", get_run_export, true},  // loads the run's scenario
    {"POST", "/api/runs/{}/replay", post_replay, true},
    {"GET", "/api/replays/{}", get_replay},
    {"POST", "/api/replays/{}/control", post_replay_control},
    {"POST", "/api/compare", post_compare, true},
    {"GET", "/api/compare/{}/export.html", get_group_export, true},
    {"POST", "/api/sweeps", post_sweep, true},
    {"POST", "/api/sweeps/validate", validate_sweep, true},
    {"GET", "/api/sweeps", list_sweeps},
    {"GET", "/api/sweeps/{}", get_sweep, true},  // an ended sweep's report may be built
    {"GET", "/api/sweeps/{}/runs", get_sweep_runs, true},  // reads the sweep's stored runs
    {"POST", "/api/sweeps/{}/control", post_sweep_control},
};

// GET only (an upgrade); the source a matched path names, or null.
struct SocketRoute {
  const char* pattern;
  std::shared_ptr<FrameSource> (*source)(RunManager&, std::int64_t id);
};

std::shared_ptr<FrameSource> live_run_source(RunManager& runs, std::int64_t id) {
  int lane = 0;
  const auto group = runs.group_of(id, lane);
  return group ? group->source(lane) : nullptr;
}
std::shared_ptr<FrameSource> replay_source(RunManager& runs, std::int64_t id) { return runs.replay(id); }

constexpr SocketRoute kSocketRoutes[] = {
    {"/ws/runs/{}", live_run_source},
    {"/ws/replays/{}", replay_source},
};

std::vector<std::string_view> segments(std::string_view path) {
  std::vector<std::string_view> out;
  size_t start = 1;
  while (start <= path.size()) {
    size_t end = path.find('/', start);
    if (end == std::string_view::npos) end = path.size();
    out.push_back(path.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

bool match(std::string_view pattern, const std::vector<std::string_view>& path, std::vector<std::string>& captures) {
  const std::vector<std::string_view> parts = segments(pattern);
  if (parts.size() != path.size()) return false;
  captures.clear();
  for (size_t i = 0; i < parts.size(); ++i) {
    if (parts[i] == "{}") {
      if (path[i].empty()) return false;
      captures.emplace_back(path[i]);
    } else if (parts[i] != path[i]) {
      return false;
    }
  }
  return true;
}

}  // namespace

std::vector<RouteInfo> api_routes() {
  std::vector<RouteInfo> routes;
  for (const Route& route : kRoutes) routes.push_back({route.verb, route.pattern});
  return routes;
}

std::vector<RouteInfo> websocket_routes() {
  std::vector<RouteInfo> routes;
  for (const SocketRoute& route : kSocketRoutes) routes.push_back({"GET", route.pattern});
  return routes;
}

std::shared_ptr<FrameSource> websocket_source(RunManager& runs, std::string_view path) {
  const std::vector<std::string_view> parts = segments(path);
  std::vector<std::string> captures;
  for (const SocketRoute& route : kSocketRoutes) {
    if (!match(route.pattern, parts, captures)) continue;
    if (const auto id = parse_id(captures.at(0)))
      if (auto source = route.source(runs, *id)) return source;
    break;
  }
  throw DomainError(Problem::not_found, "not_found", "no live run or replay at " + std::string(path));
}

bool is_slow(const ApiRequest& request) {
  std::string_view path = request.path;
  while (path.size() > 1 && path.back() == '/') path.remove_suffix(1);
  const std::vector<std::string_view> parts = segments(path);
  std::vector<std::string> captures;
  for (const Route& route : kRoutes)
    if (request.method == route.verb && match(route.pattern, parts, captures)) return route.slow;
  return false;
}

std::int64_t RouteContext::id(size_t index) const {
  const std::string& text = captures.at(index);
  const auto value = parse_id(text);
  if (!value) throw DomainError(Problem::not_found, "not_found", "no such id \"" + text + "\"", "id");
  return *value;
}

ApiResponse handle_api(RunManager& runs, const ServerInfo& info, const ApiRequest& request) {
  std::string_view path = request.path;
  while (path.size() > 1 && path.back() == '/') path.remove_suffix(1);
  const std::vector<std::string_view> parts = segments(path);
  RouteContext context{runs, info, request, {}};
  bool path_known = false;
  std::string allowed;
  try {
    for (const Route& route : kRoutes) {
      if (!match(route.pattern, parts, context.captures)) continue;
      path_known = true;
      if (request.method == route.verb) return route.handler(context);
      allowed += (allowed.empty() ? "" : ", ") + std::string(route.verb);
    }
    if (path_known)
      throw DomainError(Problem::not_allowed, "method_not_allowed",
                        request.method + " is not allowed here (allowed: " + allowed + ")");
    throw DomainError(Problem::not_found, "not_found", "no API route " + std::string(path));
  } catch (const DomainError& e) {
    return error_response(e);
  } catch (...) {
    try {
      rethrow_as_domain_error("");
    } catch (const DomainError& e) {
      return error_response(e);
    }
  }
}

}  // namespace rrlab::server
