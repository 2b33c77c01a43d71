// One HTTP connection: read a request's header (header and URL limits, bare
// LF refused), answer `Expect: 100-continue`, read the body (body limit,
// timeout), answer it (API, static file or WebSocket upgrade), then read the
// next. A request that cannot be parsed or is over a limit gets its 4xx and
// the connection closes. Deferred API answers (batch runs waited for) come
// back onto the connection's strand. Streamed answers (frame exports) are
// written chunk by chunk: each chunk is produced on an export worker, and the
// next one only once the previous one has been written (send_stream).
#include <algorithm>
#include <array>
#include <fstream>
#include <iterator>
#include <string_view>
#include <thread>

#include <rrlab/server/net/sessions.hpp>

#include <rrlab/server/app/controller.hpp>
#include <rrlab/server/app/replay_player.hpp>
#include <rrlab/server/net/static_files.hpp>

namespace rrlab::server {

namespace {

const char* status_code_name(int status) {
  switch (status) {
    case 404: return "not_found";
    case 405: return "method_not_allowed";
    case 413: return "body_too_large";
    case 414: return "url_too_long";
    case 431: return "header_too_large";
    case 503: return "busy";
    default: return "bad_request";
  }
}

// The bytes of `buffer` up to the end of the header ("\r\n\r\n"), or all of
// them while the header is incomplete.
std::string_view header_part(std::string_view buffer) {
  const auto end = buffer.find("\r\n\r\n");
  return end == std::string_view::npos ? buffer : buffer.substr(0, end + 4);
}

// A line feed without its carriage return: Beast's parser would wait for a
// "\r\n\r\n" that never comes, until the read timeout.
bool has_bare_line_feed(std::string_view header) {
  for (std::size_t lf = header.find('\n'); lf != std::string_view::npos; lf = header.find('\n', lf + 1))
    if (lf == 0 || header[lf - 1] != '\r') return true;
  return false;
}

// The request line (without its line end) as far as it has arrived.
std::string_view request_line(std::string_view buffer) {
  return buffer.substr(0, std::min(buffer.find('\n'), buffer.size()));
}

bool expects_continue(const http::request<http::string_body>& header) {
  return header.version() >= 11 && beast::iequals(header[http::field::expect], "100-continue");
}

constexpr std::string_view kContinue = "HTTP/1.1 100 Continue\r\n\r\n";

class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(tcp::socket&& socket, std::shared_ptr<ServerState> state)
      : stream_(std::move(socket)), state_(std::move(state)) {}

  void run() {
    // one of the address's connections (net/peer_limits.hpp): refused at its cap unless an idle one makes room
    address_ = remote_address();
    std::weak_ptr<HttpSession> weak = shared_from_this();
    // the flag is shared, not the session: the limits test it under their lock,
    // where the session's last reference must never be dropped (its end takes that lock)
    hold_ = state_->peers.connection(
        address_, {[waiting = waiting_for_request_] { return waiting->load(); },
                   [weak] {
                     if (auto self = weak.lock())
                       net::post(self->stream_.get_executor(), [self] {
                         if (!self->waiting_for_request_->load()) return;  // a request arrived meanwhile
                         beast::error_code ec;
                         self->stream_.socket().close(ec);
                       });
                   }});
    if (!hold_) {
      beast::error_code ec;
      stream_.socket().close(ec);
      return;
    }
    net::dispatch(stream_.get_executor(), [self = shared_from_this()] { self->guarded([&] { self->read(); }); });
  }

 private:
  // Every callback of the session goes through here: an exception closes the
  // connection instead of reaching the I/O loop.
  template <typename Step>
  void guarded(Step&& step) {
    try {
      step();
    } catch (const std::exception&) {
      close();
    }
  }

  void read() {
    *waiting_for_request_ = true;
    parser_.emplace();
    parser_->body_limit(state_->limits.body_limit);
    parser_->header_limit(static_cast<std::uint32_t>(state_->limits.header_limit));
    stream_.expires_after(state_->limits.read_timeout);
    parse_header();  // a pipelined request may be in the buffer already
  }

  void read_header_bytes() {
    const auto space = buffer_.prepare(4096);
    stream_.async_read_some(space, [self = shared_from_this()](beast::error_code ec, std::size_t n) {
      self->buffer_.commit(n);
      self->guarded([&] {
        if (ec == net::error::eof)  // as http::async_read names it
          return self->on_read_failed(self->buffer_.size() == 0 ? http::error::end_of_stream
                                                                : http::error::partial_message);
        if (ec) return self->on_read_failed(ec);
        self->parse_header();
      });
    });
  }

  // Feeds the buffered bytes to the parser until the header is complete.
  void parse_header() {
    const std::string_view buffered(static_cast<const char*>(buffer_.data().data()), buffer_.size());
    if (buffered.empty()) return read_header_bytes();
    if (has_bare_line_feed(header_part(buffered)))
      return refuse(400, "malformed_request", "lines must end with CRLF, not a bare LF");
    beast::error_code ec;
    buffer_.consume(parser_->put(buffer_.data(), ec));
    if (ec == http::error::need_more) return read_header_bytes();
    if (ec) return on_read_failed(ec);
    on_header();
  }

  void on_header() {
    *waiting_for_request_ = false;
    const auto& header = parser_->get();
    if (header.target().size() > state_->limits.url_limit) return refuse_url_too_long();
    if (!parser_->is_done() && expects_continue(header)) return send_continue();
    read_body();
  }

  // The header is acceptable (any Content-Length over the body limit has been
  // refused already): the client may send the body.
  void send_continue() {
    net::async_write(stream_, net::buffer(kContinue.data(), kContinue.size()),
                     [self = shared_from_this()](beast::error_code ec, std::size_t) {
                       if (ec) return;
                       self->guarded([&] { self->read_body(); });
                     });
  }

  void read_body() {
    stream_.expires_after(state_->limits.read_timeout);
    http::async_read(stream_, buffer_, *parser_, [self = shared_from_this()](beast::error_code ec, std::size_t) {
      self->guarded([&] {
        if (ec) return self->on_read_failed(ec);
        self->on_read();
      });
    });
  }

  // A read or parse error: an answer when the client can still read one, then
  // the connection closes.
  void on_read_failed(beast::error_code ec) {
    if (ec == http::error::end_of_stream) return close();
    if (ec == http::error::body_limit)
      return refuse(413, "body_too_large",
                    "the request body is larger than " + std::to_string(state_->limits.body_limit) + " bytes");
    if (ec == http::error::header_limit) return refuse_header_limit();
    if (ec.category() == http::make_error_code(http::error::bad_method).category())
      return refuse(400, "malformed_request", "malformed HTTP request: " + ec.message());
    // a timeout or a reset: nobody to answer
  }

  // Over the header limit: 414 when the URL alone is over its limit (or the
  // request line has not even ended), 431 otherwise. Beast consumes the
  // request line once it has parsed it; until then it is in the buffer.
  void refuse_header_limit() {
    const std::string_view buffered(static_cast<const char*>(buffer_.data().data()), buffer_.size());
    const std::string_view target = parser_->get().target();
    const std::size_t url_length = target.empty() ? request_line(buffered).size() : target.size();
    if (url_length > state_->limits.url_limit) return refuse_url_too_long();
    refuse(431, "header_too_large",
           "the request header is larger than " + std::to_string(state_->limits.header_limit) + " bytes");
  }

  void refuse_url_too_long() {
    refuse(414, "url_too_long", "the URL is longer than " + std::to_string(state_->limits.url_limit) + " bytes");
  }

  // A 4xx for a request that will not be read on: answer, then close (reading
  // and discarding what the client still sends, so that it gets the answer).
  void refuse(int status, const std::string& code, const std::string& message) {
    keep_alive_ = false;
    drain_after_write_ = true;
    version_ = 11;
    send_api(error_response(status, code, message));
  }

  // The peer's IP address ("" if the socket no longer knows it).
  std::string remote_address() {
    beast::error_code ec;
    const auto endpoint = stream_.socket().remote_endpoint(ec);
    return ec ? std::string() : endpoint.address().to_string();
  }

  void on_read() {
    http::request<http::string_body> request = parser_->release();
    keep_alive_ = request.keep_alive();
    version_ = request.version();
    const std::string target(request.target());
    const auto question = target.find('?');
    const std::string path = target.substr(0, question);

    // Host, Origin, token and Content-Type rules (net/request_guard.hpp), once per request
    const AccessDecision access = check_access(
        state_->access,
        {std::string(request.method_string()), target, std::string(request[http::field::host]),
         std::string(request[http::field::origin]), std::string(request[http::field::content_type]),
         !request.body().empty(), websocket::is_upgrade(request), std::string(request[http::field::authorization]),
         std::string(request[http::field::access_control_request_headers]), int(request.count(http::field::host)),
         int(request.count(http::field::origin))});
    access_headers_ = access.headers;
    if (access.wrong_token) {  // token guessing: 429 for a while after too many wrong ones (net/auth_throttle.hpp)
      const std::string address = remote_address();
      const auto now = AuthThrottle::Clock::now();
      if (const long wait = state_->auth_failures.blocked_for(address, now); wait > 0) {
        ApiResponse slow = error_response(
            DomainError(Problem::too_many, "too_many_attempts",
                        "too many wrong tokens from this address; try again in " + std::to_string(wait) + " s"));
        slow.headers.emplace_back("Retry-After", std::to_string(wait));
        return send_api(slow);
      }
      state_->auth_failures.failed(address, now);
    }
    if (access.status >= 400)
      return send_api(error_response(access.status, access.code, access.message, access.path));
    if (!access.allowed()) {  // a CORS preflight
      ApiResponse preflight;
      preflight.status = access.status;
      preflight.content_type.clear();
      return send_api(preflight);
    }

    if (websocket::is_upgrade(request)) {
      const auto query = question == std::string::npos ? std::map<std::string, std::string>{}
                                                       : parse_query(target.substr(question + 1));
      const auto client = query.find("client");
      return upgrade(std::move(request), path, access, client == query.end() ? "" : valid_client_name(client->second));
    }
    if (path.rfind("/api/", 0) == 0 || path == "/api") return answer_api(request, path, target, question);
    return answer_static(request, path);
  }

  void answer_api(const http::request<http::string_body>& request, const std::string& path,
                  const std::string& target, std::size_t question) {
    ApiRequest api;
    api.method = std::string(request.method_string());
    api.path = path;
    if (question != std::string::npos) api.query = parse_query(target.substr(question + 1));
    api.body = request.body();
    api.content_type = std::string(request[http::field::content_type]);
    api.accept = std::string(request[http::field::accept]);
    api.client = valid_client_name(std::string(request["Rrlab-Client"]));
    api.address = remote_address();
    ApiResponse response = is_slow(api) ? on_workers(std::move(api)) : handle_api(state_->runs, state_->info, api);
    if (response.deferred) {
      stream_.expires_never();  // a batch run may take a while
      auto self = shared_from_this();
      response.deferred([self](ApiResponse ready) {
        net::post(self->stream_.get_executor(),
                  [self, ready = std::move(ready)] {
                    // a slow route's answer may be streamed too (a sweep's runs as CSV)
                    self->guarded([&] { ready.stream ? self->send_stream(ready) : self->send_api(ready); });
                  });
      });
      return;
    }
    if (response.stream) return send_stream(response);
    send_api(response);
  }

  // Slow work (routes/routes.hpp is_slow), answered from the worker pool: the
  // I/O threads go on answering others meanwhile (503 busy when its queue is full).
  ApiResponse on_workers(ApiRequest api) {
    ApiResponse later;
    later.deferred = [state = state_, api = std::move(api)](Responder respond) mutable {
      ++state->building;
      const std::string owner = api.address;  // fair between addresses (client names share their address's turn)
      const bool queued = state->workers.post([state, api = std::move(api), respond] {
        ApiResponse response;
        try {
          if (state->limits.test_build_delay.count() > 0) std::this_thread::sleep_for(state->limits.test_build_delay);
          response = handle_api(state->runs, state->info, api);
        } catch (...) {  // handle_api answers every error; only an allocation failure lands here
          response = error_response(DomainError(Problem::internal, "internal", "the request could not be handled"));
        }
        --state->building;
        if (response.deferred)
          response.deferred(respond);  // a batch run's answer comes when it ends
        else
          respond(std::move(response));
      }, owner);
      if (!queued) {
        --state->building;
        ApiResponse busy =
            error_response(DomainError(Problem::busy, "busy", "too much slow work is waiting; try again"));
        busy.headers.emplace_back("Retry-After", "1");
        respond(std::move(busy));
      }
    };
    return later;
  }

  // A streamed answer in flight: its body, its reservation of the export
  // budget, and Beast's serializer over a buffer_body that points at the
  // current chunk.
  struct Streamed {
    std::shared_ptr<BodyStream> body;
    std::shared_ptr<ExportPool::Ticket> ticket;
    http::response<http::buffer_body> response;
    std::optional<http::response_serializer<http::buffer_body>> serializer;
    std::string chunk;
    bool more = true, header_sent = false;
    std::optional<ApiResponse> failure;  // the producer threw
  };

  // Reserves two chunks of the export budget (503 with Retry-After when it is
  // full), then produces and writes the body. HTTP/1.1: chunked transfer;
  // HTTP/1.0: the body ends when the connection closes.
  void send_stream(const ApiResponse& api) {
    auto ticket = state_->exports.reserve(2 * state_->limits.export_chunk);
    if (!ticket) {
      ApiResponse busy = error_response(DomainError(
          Problem::busy, "busy", "too many exports in progress (their memory budget is full); retry in a moment"));
      busy.headers.emplace_back("Retry-After", "1");
      return send_api(busy);
    }
    auto out = std::make_shared<Streamed>();
    out->body = api.stream;
    out->ticket = std::move(ticket);
    auto& response = out->response;
    response.result(http::status(api.status));
    response.version(version_);
    response.set(http::field::server, "rrlab/" + state_->info.version);
    if (!api.content_type.empty()) response.set(http::field::content_type, api.content_type);
    response.set(http::field::cache_control, "no-store");
    for (const auto& [name, value] : access_headers_) response.set(name, value);
    for (const auto& [name, value] : api.headers) response.set(name, value);
    if (version_ < 11) keep_alive_ = false;
    response.keep_alive(keep_alive_);
    if (version_ >= 11) response.chunked(true);
    response.body().data = nullptr;
    response.body().more = true;
    out->serializer.emplace(response);
    produce(out);
  }

  // The next chunk, on an export worker; written on this connection's strand.
  void produce(std::shared_ptr<Streamed> out) {
    const std::size_t target = state_->limits.export_chunk;
    state_->exports.post([self = shared_from_this(), out, target] {
      try {
        try {
          out->more = out->body->next(out->chunk, target);
        } catch (...) {
          rethrow_as_domain_error("");
        }
      } catch (const DomainError& e) {
        out->failure = error_response(e);
      }
      net::post(self->stream_.get_executor(), [self, out] { self->guarded([&] { self->on_produced(out); }); });
    });
  }

  void on_produced(const std::shared_ptr<Streamed>& out) {
    if (out->failure) {
      if (!out->header_sent) return send_api(*out->failure);  // nothing sent yet: a plain error answer
      return close();  // cut short: no last chunk, so the client sees an incomplete body
    }
    if (out->header_sent) return write_chunk(out);
    out->header_sent = true;
    stream_.expires_after(state_->limits.read_timeout);
    http::async_write_header(stream_, *out->serializer, [self = shared_from_this(), out](beast::error_code ec, std::size_t) {
      if (ec) return;
      self->guarded([&] { self->write_chunk(out); });
    });
  }

  // Writes the current chunk (and the last chunk once the body is complete);
  // a client that takes no bytes for the read timeout loses the connection,
  // and the export its reservation.
  void write_chunk(const std::shared_ptr<Streamed>& out) {
    if (out->chunk.empty() && out->more) return produce(out);
    auto& body = out->response.body();
    body.data = out->chunk.empty() ? nullptr : out->chunk.data();
    body.size = out->chunk.size();
    body.more = out->more;
    stream_.expires_after(state_->limits.read_timeout);
    http::async_write(stream_, *out->serializer, [self = shared_from_this(), out](beast::error_code ec, std::size_t) {
      if (ec == http::error::need_buffer) ec = {};  // the chunk is out: Beast asks for the next
      if (ec) return;
      self->guarded([&] {
        if (!out->serializer->is_done()) return self->produce(out);
        if (!self->keep_alive_) return self->close();
        self->read();
      });
    });
  }

  void send_api(const ApiResponse& api) {
    auto response = std::make_shared<http::response<http::string_body>>(http::status(api.status), version_);
    response->set(http::field::server, "rrlab/" + state_->info.version);
    if (!api.content_type.empty()) response->set(http::field::content_type, api.content_type);
    response->set(http::field::cache_control, "no-store");
    for (const auto& [name, value] : access_headers_) response->set(name, value);
    for (const auto& [name, value] : api.headers) response->set(name, value);
    response->keep_alive(keep_alive_);
    response->body() = api.body;
    response->prepare_payload();
    write(response);
  }

  void send_error(int status, const std::string& message) {
    send_api(error_response(status, status_code_name(status), message));
  }

  void answer_static(const http::request<http::string_body>& request, const std::string& path) {
    if (request.method() != http::verb::get && request.method() != http::verb::head)
      return send_error(405, "static files take GET or HEAD");
    const auto file = resolve_static(state_->web_root, path);
    if (!file) return send_error(404, "no file " + path);
    http::file_body::value_type body;
    beast::error_code ec;
    body.open(file->path.c_str(), beast::file_mode::scan, ec);
    if (ec) return send_error(404, "no file " + path);
    const auto size = body.size();
    const bool unchanged = request[http::field::if_none_match] == file->etag;
    std::string html;  // an HTML page's import map hashes go into its policy
    if (file->mime_type.rfind("text/html", 0) == 0 && size <= (1u << 20)) {
      std::ifstream in(file->path, std::ios::binary);
      html.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    const auto security = static_security_headers(html);
    if (request.method() == http::verb::head || unchanged) {
      auto response = std::make_shared<http::response<http::empty_body>>(
          unchanged ? http::status::not_modified : http::status::ok, version_);
      response->set(http::field::content_type, file->mime_type);
      response->set(http::field::cache_control, kStaticCacheControl);
      response->set(http::field::etag, file->etag);
      for (const auto& [name, value] : security) response->set(name, value);
      if (!unchanged) response->content_length(size);
      response->keep_alive(keep_alive_);
      return write(response);
    }
    auto response = std::make_shared<http::response<http::file_body>>(
        std::piecewise_construct, std::make_tuple(std::move(body)), std::make_tuple(http::status::ok, version_));
    response->set(http::field::server, "rrlab/" + state_->info.version);
    response->set(http::field::content_type, file->mime_type);
    response->set(http::field::cache_control, kStaticCacheControl);
    response->set(http::field::etag, file->etag);
    for (const auto& [name, value] : security) response->set(name, value);
    response->content_length(size);
    response->keep_alive(keep_alive_);
    write(response);
  }

  // A WebSocket route of the router (websocket_routes: /ws/runs/{id}, /ws/replays/{id}).
  // `access.may_steer` false: a tokenless watcher (--public-read); `client`: its name (app/controller.hpp).
  void upgrade(http::request<http::string_body>&& request, const std::string& path, const AccessDecision& access,
               const std::string& client) {
    std::shared_ptr<FrameSource> source;
    try {
      source = websocket_source(state_->runs, path);  // routes/router.cpp
    } catch (const DomainError& e) {
      return send_api(error_response(e));
    }
    std::string refused;
    const Standing standing = access.token_holder ? Standing::token_holder
                              : access.may_steer  ? Standing::anonymous
                                                  : Standing::watcher;
    PeerLimits::Hold socket_hold = state_->peers.websocket(address_, client, standing, refused);
    if (!socket_hold) return send_error(503, refused);
    double display_hz = state_->runs.limits().default_display_hz;
    start_websocket_session(std::move(stream_), state_, std::move(source), std::move(request), display_hz,
                            {access.may_steer, client}, {std::move(hold_), std::move(socket_hold)});
  }

  template <typename Response>
  void write(std::shared_ptr<Response> response) {
    stream_.expires_after(state_->limits.read_timeout);
    http::async_write(stream_, *response, [self = shared_from_this(), response](beast::error_code ec, std::size_t) {
      if (ec) return;
      self->guarded([&] {
        if (self->drain_after_write_) return self->drain();
        if (!self->keep_alive_) return self->close();
        self->read();
      });
    });
  }

  // After refusing a body mid-upload: stop sending, read and discard what the
  // client still sends (briefly), so that closing does not reset the
  // connection before the client has read the answer.
  void drain() {
    if (!drained_once_) {
      drained_once_ = true;
      close();
      stream_.expires_after(std::chrono::seconds(2));
    }
    stream_.async_read_some(net::buffer(discard_), [self = shared_from_this()](beast::error_code ec, std::size_t) {
      if (!ec) self->drain();
    });
  }

  void close() {
    beast::error_code ec;
    stream_.socket().shutdown(tcp::socket::shutdown_send, ec);
  }

  beast::tcp_stream stream_;
  beast::flat_buffer buffer_;
  std::shared_ptr<ServerState> state_;
  std::string address_;
  PeerLimits::Hold hold_;                         // this connection's place among its address's
  // between requests: may be closed for a newer connection (net/peer_limits.hpp)
  std::shared_ptr<std::atomic<bool>> waiting_for_request_ = std::make_shared<std::atomic<bool>>(false);
  std::optional<http::request_parser<http::string_body>> parser_;
  std::vector<std::pair<std::string, std::string>> access_headers_;  // CORS, for an --allow-origin origin
  bool keep_alive_ = true, drain_after_write_ = false, drained_once_ = false;
  unsigned version_ = 11;
  std::array<char, 16384> discard_{};
};

}  // namespace

void start_http_session(tcp::socket&& socket, std::shared_ptr<ServerState> state) {
  std::make_shared<HttpSession>(std::move(socket), std::move(state))->run();
}

}  // namespace rrlab::server
