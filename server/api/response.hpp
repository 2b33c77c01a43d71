// A response as plain data (the network layer writes it): a JSON or text
// body now, one that comes later (deferred), or one streamed piece by piece.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace rrlab::server {

// The REST and WebSocket contract's version, in GET /api/health: raised when
// a response changes shape. 2: stored frames have the stream's shape (metrics
// nested, diagnostics an array).
inline constexpr int kApiVersion = 2;

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

ApiResponse json_response(int status, const nlohmann::json& body);
// JSON text of a document that may quote client bytes (error messages, paths):
// invalid UTF-8 is replaced instead of throwing.
std::string safe_dump(const nlohmann::json& body);

}  // namespace rrlab::server
