#include <rrlab/methods/registry_json.hpp>
#include <rrlab/server/routes/routes.hpp>

namespace rrlab::server {

ApiResponse get_health(RouteContext& c) {
  const double uptime =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - c.info.started).count();
  return json_response(200, {{"status", "ok"},
                             {"version", c.info.version},
                             {"api_version", kApiVersion},
                             {"uptime_s", uptime},
                             {"websockets", c.info.websockets ? c.info.websockets->load() : 0},
                             {"building", c.info.building ? c.info.building->load() : 0}});
}

ApiResponse get_methods(RouteContext&) { return json_response(200, methods_json()); }

}  // namespace rrlab::server
