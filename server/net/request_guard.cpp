#include <rrlab/server/net/request_guard.hpp>

#include <algorithm>
#include <cctype>
#include <optional>

namespace rrlab::server {

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

// Client bytes quoted in a message: at most 100 characters.
std::string quote(const std::string& s) { return "\"" + (s.size() > 100 ? s.substr(0, 100) + "..." : s) + "\""; }

struct Authority {
  std::string name;  // lower case; an IPv6 address in brackets
  std::optional<int> port;
};

// "name", "name:port", "[v6]", "[v6]:port"; nothing if malformed.
std::optional<Authority> parse_authority(const std::string& text) {
  Authority a;
  std::string rest;
  if (!text.empty() && text[0] == '[') {
    const auto close = text.find(']');
    if (close == std::string::npos) return std::nullopt;
    a.name = lower(text.substr(0, close + 1));
    rest = text.substr(close + 1);
  } else {
    const auto colon = text.find(':');
    a.name = lower(text.substr(0, colon));
    rest = colon == std::string::npos ? "" : text.substr(colon);
  }
  if (a.name.empty() || a.name == "[]") return std::nullopt;
  for (char c : a.name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_' || c == '[' || c == ']' ||
          c == ':'))
      return std::nullopt;
  if (rest.empty()) return a;
  if (rest[0] != ':' || rest.size() < 2 || rest.size() > 6) return std::nullopt;
  int port = 0;
  for (char c : rest.substr(1)) {
    if (c < '0' || c > '9') return std::nullopt;
    port = port * 10 + (c - '0');
  }
  if (port > 65535) return std::nullopt;
  a.port = port;
  return a;
}

std::string bracketed(const std::string& address) {
  // an IPv6 address (two colons or more) without brackets
  const bool v6 = std::count(address.begin(), address.end(), ':') >= 2;
  return v6 && address.front() != '[' ? "[" + address + "]" : address;
}

// Rule 1 for an authority; `default_port` when it names none. An --allow-host
// name without a port names any port, unless `only_port` says which (for an
// origin: the port the request was sent to, so that another server on that
// host, http://lab-pc:3000, is not this one's origin).
bool names_this_server(const AccessConfig& config, const Authority& a, int default_port,
                       std::optional<int> only_port = std::nullopt) {
  const int port = a.port.value_or(default_port);
  const std::string bound = lower(bracketed(config.bind_host));
  if (port == config.port && (a.name == "localhost" || a.name == "127.0.0.1" || a.name == "[::1]" || a.name == bound))
    return true;
  for (const std::string& allowed : config.allow_hosts) {
    const auto named = parse_authority(bracketed(trim(allowed)));
    if (!named || named->name != a.name) continue;
    const std::optional<int> allowed_port = named->port ? named->port : only_port;
    if (!allowed_port || port == *allowed_port) return true;
  }
  return false;
}

struct Origin {
  std::string scheme;
  Authority authority;
};

std::optional<Origin> parse_origin(const std::string& text) {
  const auto sep = text.find("://");
  if (sep == std::string::npos || sep == 0) return std::nullopt;
  Origin o;
  o.scheme = lower(text.substr(0, sep));
  std::string rest = text.substr(sep + 3);
  if (!rest.empty() && rest.back() == '/') rest.pop_back();
  const auto authority = parse_authority(rest);
  if (!authority) return std::nullopt;
  o.authority = *authority;
  return o;
}

int default_port(const std::string& scheme) { return scheme == "https" ? 443 : scheme == "http" ? 80 : -1; }

bool is_allowed_origin(const AccessConfig& config, const std::string& normalized) {
  return !normalized.empty() && std::any_of(config.allow_origins.begin(), config.allow_origins.end(),
                                            [&](const std::string& o) { return normalize_origin(o) == normalized; });
}

std::string hosts_for_message(const AccessConfig& config) {
  std::vector<std::string> hosts = {"localhost", "127.0.0.1"};
  if (lower(bracketed(config.bind_host)) != "127.0.0.1") hosts.push_back(bracketed(config.bind_host));
  std::string names;
  for (const auto& h : hosts)
    names.append(names.empty() ? "" : ", ").append(h).append(":").append(std::to_string(config.port));
  for (const auto& h : config.allow_hosts) names.append(", ").append(h);
  return names;
}

AccessDecision refuse(int status, std::string code, std::string message) {
  AccessDecision d;
  d.status = status;
  d.code = std::move(code);
  d.message = std::move(message);
  return d;
}

// Rule 0: `fields` copies of a header that may come once.
AccessDecision duplicate_header(const std::string& name, int fields, const std::string& allowed) {
  AccessDecision refused = refuse(
      400, "duplicate_header", "the request has " + std::to_string(fields) + " " + name + " headers; send " + allowed);
  refused.path = name;
  return refused;
}

// The value of the query parameter `name` (percent-decoded), if present.
std::optional<std::string> query_value(const std::string& target, const std::string& name) {
  const auto question = target.find('?');
  if (question == std::string::npos) return std::nullopt;
  const std::string query = target.substr(question + 1);
  for (std::size_t start = 0; start <= query.size();) {
    std::size_t end = query.find('&', start);
    if (end == std::string::npos) end = query.size();
    const std::string pair = query.substr(start, end - start);
    const auto eq = pair.find('=');
    if (pair.substr(0, eq) == name) {
      const std::string raw = eq == std::string::npos ? "" : pair.substr(eq + 1);
      std::string value;
      for (std::size_t i = 0; i < raw.size(); ++i) {
        if (raw[i] == '%' && i + 2 < raw.size() && std::isxdigit(static_cast<unsigned char>(raw[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(raw[i + 2]))) {
          value.push_back(char(std::stoi(raw.substr(i + 1, 2), nullptr, 16)));
          i += 2;
        } else {
          value.push_back(raw[i] == '+' ? ' ' : raw[i]);
        }
      }
      return value;
    }
    start = end + 1;
  }
  return std::nullopt;
}

// The token a request presents: "Bearer TOKEN" (scheme case-insensitive), or
// for an upgrade the `token` query parameter; nothing if none.
std::optional<std::string> presented_token(const AccessRequest& request) {
  const std::string header = trim(request.authorization);
  if (!header.empty()) {
    const auto space = header.find(' ');
    if (space == std::string::npos || lower(header.substr(0, space)) != "bearer") return std::string();  // wrong
    return trim(header.substr(space + 1));
  }
  if (request.upgrade) return query_value(request.target, "token");
  return std::nullopt;
}

}  // namespace

bool constant_time_equals(const std::string& a, const std::string& b) {
  // every byte of the longer string is looked at, whatever the contents
  const std::size_t n = std::max(a.size(), b.size());
  volatile unsigned char diff = a.size() == b.size() ? 0 : 1;
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char x = i < a.size() ? static_cast<unsigned char>(a[i]) : 0;
    const unsigned char y = i < b.size() ? static_cast<unsigned char>(b[i]) : 0;
    diff = diff | (x ^ y);
  }
  return diff == 0;
}

std::string token_problem(const std::string& token) {
  if (token.empty()) return "the token is empty";
  if (token.size() > 512) return "the token is longer than 512 characters";
  for (char c : token)
    if (c < 0x21 || c > 0x7e) return "the token may hold visible ASCII characters only (no spaces)";
  // the token's length is what makes guessing infeasible (docs/api.md, Access): 16 hex digits are 64 bits
  if (token.size() < 16) return "the token is shorter than 16 characters (make one with: openssl rand -hex 24)";
  return "";
}

bool is_loopback_host(const std::string& host) {
  return host.rfind("127.", 0) == 0 || host == "::1" || host == "[::1]" || lower(host) == "localhost";
}

std::string normalize_origin(const std::string& origin) {
  const auto o = parse_origin(trim(origin));
  if (!o || default_port(o->scheme) < 0) return "";
  std::string text = o->scheme + "://" + o->authority.name;
  if (o->authority.port && *o->authority.port != default_port(o->scheme))
    text.append(":").append(std::to_string(*o->authority.port));
  return text;
}

AccessDecision check_access(const AccessConfig& config, const AccessRequest& request) {
  // 0. One Host, one Origin
  if (request.host_fields > 1) return duplicate_header("Host", request.host_fields, "exactly one");
  if (request.origin_fields > 1) return duplicate_header("Origin", request.origin_fields, "at most one");

  // 1. Host
  int request_port = config.port;  // the port the client addressed
  if (request.host.empty()) {
    if (!is_loopback_host(config.bind_host))
      return refuse(400, "missing_host", "the request needs a Host header naming this server");
  } else {
    const auto authority = parse_authority(trim(request.host));
    if (authority) request_port = authority->port.value_or(80);
    if (!authority || !names_this_server(config, *authority, 80))
      return refuse(421, "misdirected",
                    "Host " + quote(request.host) + " does not name this server (" + hosts_for_message(config) +
                        "); start rrlab serve with --allow-host NAME to accept another name");
  }

  // 2. Origin
  AccessDecision decision;
  if (!request.origin.empty()) {
    const std::string normalized = normalize_origin(request.origin);
    const auto origin = parse_origin(trim(request.origin));
    const bool own = origin && origin->scheme == "http" && names_this_server(config, origin->authority, 80, request_port);
    const bool listed = is_allowed_origin(config, normalized);
    if (listed) {
      decision.headers = {{"Access-Control-Allow-Origin", trim(request.origin)}, {"Vary", "Origin"}};
      if (request.method == "OPTIONS") {
        decision.status = 204;
        decision.headers.push_back({"Access-Control-Allow-Methods", "GET, HEAD, POST, PUT, PATCH, DELETE"});
        // Content-Type, and the token and client name headers when the page asks to send them
        std::string allowed = "Content-Type";
        const std::string requested = "," + lower(request.request_headers) + ",";
        for (const char* name : {"Authorization", "Rrlab-Client"}) {
          std::string token = "," + lower(name) + ",";
          std::string compact = requested;
          compact.erase(std::remove_if(compact.begin(), compact.end(), [](char c) { return c == ' ' || c == '\t'; }),
                        compact.end());
          if (compact.find(token) != std::string::npos) allowed.append(", ").append(name);
        }
        decision.headers.push_back({"Access-Control-Allow-Headers", allowed});
        decision.headers.push_back({"Access-Control-Max-Age", "600"});
        return decision;
      }
    }
    const bool safe = request.method == "GET" || request.method == "HEAD" || request.method == "OPTIONS";
    if ((request.upgrade || !safe) && !own && !listed)
      return refuse(403, "forbidden_origin",
                    "Origin " + quote(request.origin) +
                        " may not change this server or open its WebSockets; start rrlab serve with "
                        "--allow-origin ORIGIN to accept it");
  }

  const std::string path = request.target.substr(0, request.target.find('?'));

  // 3. Token
  if (!config.token.empty()) {
    const bool safe = request.method == "GET" || request.method == "HEAD" || request.method == "OPTIONS";
    const bool api = path == "/api" || path.rfind("/api/", 0) == 0;
    const auto token = presented_token(request);
    const bool valid = token && constant_time_equals(*token, config.token);
    const bool open = safe && !request.upgrade && (!api || path == "/api/health" || path == "/api/health/");
    const bool readable = safe && config.public_read;
    decision.token_presented = token.has_value();
    if (token && !valid) {
      AccessDecision refused = refuse(401, "unauthorized",
                                      "the token is wrong: send the token this server was started with "
                                      "(--token or RRLAB_TOKEN) as Authorization: Bearer TOKEN");
      refused.headers = decision.headers;
      refused.headers.push_back({"WWW-Authenticate", "Bearer realm=\"rrlab\", error=\"invalid_token\""});
      refused.token_presented = refused.wrong_token = true;
      return refused;
    }
    if (!valid && !open && !readable) {
      AccessDecision refused =
          refuse(401, "unauthorized",
                 std::string("this server requires a token ") +
                     (safe ? "to read" : "for changes") +
                     ": send Authorization: Bearer TOKEN (a WebSocket may pass it as the query parameter token=TOKEN)");
      refused.headers = decision.headers;
      refused.headers.push_back({"WWW-Authenticate", "Bearer realm=\"rrlab\""});
      return refused;
    }
    decision.may_steer = decision.token_holder = valid;
  }

  // 4. Content-Type of API bodies
  if (request.has_body && (path == "/api" || path.rfind("/api/", 0) == 0)) {
    const std::string media = lower(trim(request.content_type.substr(0, request.content_type.find(';'))));
    if (media != "application/json") {
      AccessDecision refused = refuse(415, "unsupported_media_type",
                                      "the Content-Type header must be application/json for a request body" +
                                          (request.content_type.empty() ? std::string(" (none was given)")
                                                                        : ", not " + quote(request.content_type)));
      refused.headers = decision.headers;
      return refused;
    }
  }
  return decision;
}

}  // namespace rrlab::server
