// Where the app's domain errors meet HTTP: the one table from Problem to
// status, and the error answers of REST and of the WebSocket messages.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include <rrlab/server/api/errors.hpp>
#include <rrlab/server/api/response.hpp>

namespace rrlab::server {

// The HTTP status of a Problem (kHttpStatus in http_errors.cpp).
int http_status(Problem problem);

// A 4xx/5xx answer: {"error": {"code", "message", "path"}}, plus the members
// of the error's detail if any (a refused limit: {"limit", "requested", "allowed", ...}).
ApiResponse error_response(const DomainError& error);
// The same answer for a refusal of the network layer that is no domain
// problem (a header too large, a bad token), with its own status.
ApiResponse error_response(int status, const std::string& code, const std::string& message,
                           const std::string& path = "");

// WebSocket replies: {"type": "error", "error": {code, message, path}} (the
// error object of REST, without a status), and {"type": "ack", "status":
// handle()} unless handle throws (engine errors are mapped as for REST,
// anything else is "internal").
nlohmann::json socket_error(const DomainError& error);
nlohmann::json socket_reply(const std::function<nlohmann::json()>& handle);

}  // namespace rrlab::server
