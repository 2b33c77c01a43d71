// Who may talk to the server: the Host, Origin and Content-Type rules that
// keep other web pages (and DNS rebinding) from driving it. Plain strings in,
// a decision out; no Beast, so that the rules are tested as a table.
//
// 1. Host must name this server: localhost, 127.0.0.1, [::1] or the --host
//    address with the bound port, or an --allow-host name (any port). Else
//    421 "misdirected". No Host at all: allowed on a loopback bind only
//    (browsers always send one), else 400 "missing_host".
// 2. A mutating request (any method but GET, HEAD, OPTIONS) and every
//    WebSocket upgrade that carries an Origin must come from this server's
//    own origin (http://HOST where HOST passes rule 1) or an --allow-origin
//    origin. Else 403 "forbidden_origin". No Origin (curl, scripts): allowed.
// 3. An /api request with a body needs Content-Type application/json
//    (parameters allowed). Else 415 "unsupported_media_type".
// CORS: only for --allow-origin origins, which get Access-Control-Allow-Origin
// on every answer and a 204 answer to OPTIONS (the preflight).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace rrlab::server {

struct AccessConfig {
  std::string bind_host = "127.0.0.1";     // the --host value
  unsigned short port = 0;                 // the bound port
  std::vector<std::string> allow_hosts;    // --allow-host NAME
  std::vector<std::string> allow_origins;  // --allow-origin ORIGIN (scheme://host[:port])
};

// Header values as received; empty: the header is absent.
struct AccessRequest {
  std::string method, target, host, origin, content_type;
  bool has_body = false;
  bool upgrade = false;  // a WebSocket upgrade
};

struct AccessDecision {
  int status = 0;  // 0: go on; 204: answer the preflight now; >= 400: refuse
  std::string code, message;
  std::vector<std::pair<std::string, std::string>> headers;  // add to the answer (CORS)
  bool allowed() const { return status == 0; }
};

AccessDecision check_access(const AccessConfig& config, const AccessRequest& request);

// An --allow-origin value as compared: lower case, no trailing slash; empty if
// it is not scheme://host[:port].
std::string normalize_origin(const std::string& origin);

}  // namespace rrlab::server
