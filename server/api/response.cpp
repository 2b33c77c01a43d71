#include <rrlab/server/api/response.hpp>

namespace rrlab::server {

ApiResponse json_response(int status, const nlohmann::json& body) {
  ApiResponse r;
  r.status = status;
  r.body = safe_dump(body);
  return r;
}

std::string safe_dump(const nlohmann::json& body) {
  return body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace rrlab::server
