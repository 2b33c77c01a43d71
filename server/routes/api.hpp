// The HTTP-independent face of the server: requests and responses as plain
// data, so that routes and run management never include Beast.
#pragma once

#include <functional>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string_view>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace rrlab::storage {
struct Outcome;
}

namespace rrlab::server {

// The REST and WebSocket contract's version, in GET /api/health: raised when
// a response changes shape. 2: stored frames have the stream's shape (metrics
// nested, diagnostics an array).
inline constexpr int kApiVersion = 2;

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

struct ApiResponse;

// A body produced piece by piece (a frame export): the network layer calls
// next() on an export worker (app/export_pool.hpp), never on an I/O thread,
// and calls it again only once the previous piece has been written.
class BodyStream {
 public:
  virtual ~BodyStream() = default;
  // Replaces `out` with the next piece, about `target` bytes (more by at most
  // one record); false once the body is complete (`out` holds its last piece,
  // possibly empty). A throw after the first piece aborts the connection: the
  // client sees a body cut short, never a well-formed partial one.
  virtual bool next(std::string& out, std::size_t target) = 0;
};
// A response that is ready later (a batch run that is waited for): the route
// hands over a function that will be called once with the response.
using Responder = std::function<void(ApiResponse)>;

struct ApiResponse {
  int status = 200;
  std::string content_type = "application/json";
  std::string body;
  std::function<void(Responder)> deferred;  // set: the body comes later
  std::shared_ptr<BodyStream> stream;        // set: the body is streamed (chunked), `body` unused
  std::vector<std::pair<std::string, std::string>> headers;  // extra header fields (Retry-After)
};

// A 4xx/5xx answer: {"error": {"code", "message", "path"}}, plus the members
// of `detail` if any (a refused limit: {"limit", "requested", "allowed", ...}).
class ApiError : public std::runtime_error {
 public:
  ApiError(int status, std::string code, const std::string& message, std::string path = "",
           nlohmann::json detail = nullptr)
      : std::runtime_error(message),
        status_(status),
        code_(std::move(code)),
        path_(std::move(path)),
        detail_(std::move(detail)) {}
  int status() const { return status_; }
  const std::string& code() const { return code_; }
  const std::string& path() const { return path_; }
  const nlohmann::json& detail() const { return detail_; }

 private:
  int status_;
  std::string code_, path_;
  nlohmann::json detail_;
};

ApiResponse json_response(int status, const nlohmann::json& body);
// JSON text of a document that may quote client bytes (error messages, paths):
// invalid UTF-8 is replaced instead of throwing.
std::string safe_dump(const nlohmann::json& body);
ApiResponse error_response(const ApiError& error);
// WebSocket replies: {"type": "error", "error": {code, message, path}}, and
// {"type": "ack", "status": handle()} unless handle throws (engine errors are
// mapped as for REST, anything else is "internal").
nlohmann::json socket_error(const ApiError& error);
nlohmann::json socket_reply(const std::function<nlohmann::json()>& handle);
// Parses JSON text sent by a client (a request body, a WebSocket message):
// anything the parser refuses, numbers out of double's range included, is a
// 400 "malformed_json" ApiError with a plain message naming the 1-based byte
// where the parser stopped ("number out of range at byte 12": the number's
// last digit), never the parser's exception text. A document nested deeper
// than kMaxJsonDepth (64) levels is a 400 "too_deep" naming the byte of the
// bracket that opens the level too many, found before the parser runs.
nlohmann::json parse_client_json(const std::string& text);
// Parses a JSON body (parse_client_json; an empty body is 400 too).
nlohmann::json parse_body(const ApiRequest& request);
// A run or replay id from a path segment: 1 to 18 decimal digits.
std::optional<std::int64_t> parse_id(std::string_view text);

// Splits "a=1&b=x%20y" into decoded pairs.
std::map<std::string, std::string> parse_query(const std::string& query);

// The status to answer once queued work has settled (storage/completion.hpp):
// the work's own result if it has one, else `status`. Input that could not be
// stored throws 503 storage_full or storage_readonly (the condition may
// pass), else 500 storage.
nlohmann::json settled_status(const nlohmann::json& status, const storage::Outcome& outcome, const std::string& path);

// Maps engine errors (ScenarioError, ParamError, InputStateError) to ApiErrors,
// prefixing JSON paths with `prefix`.
[[noreturn]] void rethrow_as_api_error(const std::string& prefix, int validation_status = 400);

}  // namespace rrlab::server
