#include <rrlab/server/routes/http_errors.hpp>

#include <cstddef>
#include <iterator>
#include <utility>

namespace rrlab::server {

namespace {

// Problem → HTTP status: the only place the statuses of domain errors are written.
constexpr std::pair<Problem, int> kHttpStatus[] = {
    {Problem::invalid, 400},
    {Problem::unauthorized, 401},
    {Problem::not_found, 404},
    {Problem::not_allowed, 405},
    {Problem::conflict, 409},
    {Problem::too_large, 413},
    {Problem::unprocessable, 422},
    {Problem::too_many, 429},
    {Problem::busy, 503},
    {Problem::unavailable, 503},
    {Problem::storage_full, 503},
    {Problem::storage_readonly, 503},
    {Problem::quota, 507},
    {Problem::storage, 500},
    {Problem::internal, 500},
};

// one row per Problem, in the enum's order (so the status is an index away)
constexpr bool rows_in_order() {
  for (std::size_t i = 0; i < std::size(kHttpStatus); ++i)
    if (std::size_t(kHttpStatus[i].first) != i) return false;
  return std::size(kHttpStatus) == std::size_t(Problem::internal) + 1;
}
static_assert(rows_in_order(), "kHttpStatus needs one row per Problem, in the enum's order");

nlohmann::json error_object(const std::string& code, const std::string& message, const std::string& path,
                            const nlohmann::json& detail) {
  nlohmann::json out = {{"code", code}, {"message", message}, {"path", path}};
  if (detail.is_object())
    for (const auto& [key, value] : detail.items()) out.emplace(key, value);  // never over code/message/path
  return out;
}

nlohmann::json error_object(const DomainError& e) { return error_object(e.code(), e.what(), e.path(), e.detail()); }

}  // namespace

int http_status(Problem problem) { return kHttpStatus[std::size_t(problem)].second; }

ApiResponse error_response(const DomainError& e) {
  return json_response(http_status(e.problem()), {{"error", error_object(e)}});
}

ApiResponse error_response(int status, const std::string& code, const std::string& message, const std::string& path) {
  return json_response(status, {{"error", error_object(code, message, path, nullptr)}});
}

nlohmann::json socket_error(const DomainError& e) { return {{"type", "error"}, {"error", error_object(e)}}; }

nlohmann::json socket_reply(const std::function<nlohmann::json()>& handle) {
  try {
    try {
      return {{"type", "ack"}, {"status", handle()}};
    } catch (...) {
      rethrow_as_domain_error("");
    }
  } catch (const DomainError& e) {
    return socket_error(e);
  }
}

}  // namespace rrlab::server
