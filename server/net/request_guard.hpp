// Who may talk to the server: the Host, Origin and Content-Type rules that
// keep other web pages (and DNS rebinding) from driving it. Plain strings in,
// a decision out; no Beast, so that the rules are tested as a table.
//
// 0. At most one Host and one Origin field (RFC 9112: a request with two
//    Hosts is refused; with two Origins, the rules below would judge one and
//    a proxy or browser may act on the other). Else 400 "duplicate_header".
// 1. Host must name this server: localhost, 127.0.0.1, [::1] or the --host
//    address with the bound port, or an --allow-host name (any port). Else
//    421 "misdirected". No Host at all: allowed on a loopback bind only
//    (browsers always send one), else 400 "missing_host".
// 2. A mutating request (any method but GET, HEAD, OPTIONS) and every
//    WebSocket upgrade that carries an Origin must come from this server's
//    own origin (http://HOST where HOST passes rule 1; for an --allow-host
//    name without a port, only with the port the request was sent to) or an
//    --allow-origin origin. Else 403 "forbidden_origin". No Origin (curl, scripts): allowed.
// 3. With a token (--token or RRLAB_TOKEN), a request needs
//    `Authorization: Bearer TOKEN` (a WebSocket upgrade: that header or the
//    query parameter token=TOKEN, which browsers can send) when it is
//    - a mutating request (any method but GET, HEAD, OPTIONS), or
//    - a read of /api (GET, HEAD, OPTIONS) or a WebSocket upgrade, unless
//      --public-read: then a tokenless WebSocket watches only (may_steer
//      false: its inputs and control messages are refused).
//    Open without a token: GET/HEAD /api/health (container health checks) and
//    static files (the dashboard must load to ask for the token). Else 401
//    "unauthorized" (a wrong token is 401 even where none is needed). Tokens
//    are compared in constant time.
// 4. An /api request with a body needs Content-Type application/json
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
  std::string token;                       // --token / RRLAB_TOKEN; empty: no token needed
  bool public_read = false;                // --public-read: reads need no token
};

// Header values as received; empty: the header is absent.
struct AccessRequest {
  std::string method, target, host, origin, content_type;
  bool has_body = false;
  bool upgrade = false;  // a WebSocket upgrade
  std::string authorization;  // the Authorization header
  std::string request_headers;  // Access-Control-Request-Headers (a preflight)
  int host_fields = 0, origin_fields = 0;  // how many Host and Origin fields came (`host`, `origin`: the first)
};

struct AccessDecision {
  int status = 0;  // 0: go on; 204: answer the preflight now; >= 400: refuse
  std::string code, message;
  std::string path;  // the header at fault (the error body's "path"), if one is
  std::vector<std::pair<std::string, std::string>> headers;  // add to the answer (CORS)
  bool may_steer = true;  // a WebSocket upgrade: its messages may steer (false: watch only)
  bool token_presented = false;  // a token was sent (right or wrong): the throttle applies (net/auth_throttle.hpp)
  bool wrong_token = false;      // ... and it was wrong
  bool token_holder = false;     // the server has a token and this request sent it (net/peer_limits.hpp)
  bool allowed() const { return status == 0; }
};

AccessDecision check_access(const AccessConfig& config, const AccessRequest& request);

// Equal strings, in a time that depends on the lengths only, never on where
// the first difference is (for tokens).
bool constant_time_equals(const std::string& a, const std::string& b);

// A token as accepted by --token: 1 to 512 visible ASCII characters (it must
// fit an HTTP header and a URL query unescaped); else the reason it is not.
std::string token_problem(const std::string& token);

// An address that only this machine reaches: 127.0.0.0/8, ::1, localhost.
bool is_loopback_host(const std::string& host);

// An --allow-origin value as compared: lower case, no trailing slash; empty if
// it is not scheme://host[:port].
std::string normalize_origin(const std::string& origin);

}  // namespace rrlab::server
