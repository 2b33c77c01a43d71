// A request as plain data (no Beast: the network layer fills it in), and the
// parsing of what a client sends: JSON text, ids in paths, query strings.
#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

namespace rrlab::server {

struct ApiRequest {
  std::string method;  // GET, POST, ...
  std::string path;    // without the query
  std::map<std::string, std::string> query;
  std::string body;
  std::string content_type, accept;
  std::string client;   // the Rrlab-Client header, if a valid name (app/controller.hpp); else empty
  std::string address;  // the peer's IP address
  // Whose request this is, for per-client limits: the client name, else "@ADDRESS".
  std::string owner() const { return client.empty() ? "@" + address : client; }
};

// Parses JSON text sent by a client (a request body, a WebSocket message):
// anything the parser refuses, numbers out of double's range included, is an
// invalid "malformed_json" DomainError (400) with a plain message naming the
// 1-based byte where the parser stopped ("number out of range at byte 12":
// the number's last digit), never the parser's exception text. A document
// nested deeper than kMaxJsonDepth (64) levels is an invalid "too_deep"
// naming the byte of the bracket that opens the level too many, found before
// the parser runs.
nlohmann::json parse_client_json(const std::string& text);
// Parses a JSON body (parse_client_json; an empty body is invalid too).
nlohmann::json parse_body(const ApiRequest& request);
// A run or replay id from a path segment: 1 to 18 decimal digits.
std::optional<std::int64_t> parse_id(std::string_view text);

// Splits "a=1&b=x%20y" into decoded pairs.
std::map<std::string, std::string> parse_query(const std::string& query);

}  // namespace rrlab::server
