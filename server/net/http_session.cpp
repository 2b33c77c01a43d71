// One HTTP connection: read a request (body limit, timeout), answer it (API,
// static file or WebSocket upgrade), then read the next. Deferred API answers
// (batch runs waited for) come back onto the connection's strand.
#include "net/sessions.hpp"
#include <array>

#include "app/replay_player.hpp"
#include "net/static_files.hpp"

namespace rrlab::server {

namespace {

const char* status_code_name(int status) {
  switch (status) {
    case 404: return "not_found";
    case 405: return "method_not_allowed";
    case 413: return "body_too_large";
    case 503: return "busy";
    default: return "bad_request";
  }
}

class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(tcp::socket&& socket, std::shared_ptr<ServerState> state)
      : stream_(std::move(socket)), state_(std::move(state)) {}

  void run() { net::dispatch(stream_.get_executor(), [self = shared_from_this()] { self->read(); }); }

 private:
  void read() {
    parser_.emplace();
    parser_->body_limit(state_->limits.body_limit);
    parser_->header_limit(16 * 1024);
    stream_.expires_after(state_->limits.read_timeout);
    http::async_read(stream_, buffer_, *parser_, [self = shared_from_this()](beast::error_code ec, std::size_t) {
      try {
        self->on_read(ec);
      } catch (const std::exception&) {
        self->close();  // never let a handler throw into the I/O loop
      }
    });
  }

  void on_read(beast::error_code ec) {
    if (ec == http::error::end_of_stream) return close();
    if (ec == http::error::body_limit) {
      keep_alive_ = false;
      drain_after_write_ = true;
      return send_error(413, "the request body is larger than " + std::to_string(state_->limits.body_limit) +
                                 " bytes");
    }
    if (ec) return;  // timeout or reset: drop the connection
    http::request<http::string_body> request = parser_->release();
    keep_alive_ = request.keep_alive();
    version_ = request.version();
    const std::string target(request.target());
    const auto question = target.find('?');
    const std::string path = target.substr(0, question);

    // Host, Origin and Content-Type rules (net/request_guard.hpp), once per request
    const AccessDecision access = check_access(
        state_->access, {std::string(request.method_string()), target, std::string(request[http::field::host]),
                         std::string(request[http::field::origin]), std::string(request[http::field::content_type]),
                         !request.body().empty(), websocket::is_upgrade(request)});
    access_headers_ = access.headers;
    if (access.status >= 400) return send_api(error_response(ApiError(access.status, access.code, access.message)));
    if (!access.allowed()) return send_api(ApiResponse{access.status, "", "", {}});  // a CORS preflight

    if (websocket::is_upgrade(request)) return upgrade(std::move(request), path);
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
    ApiResponse response = handle_api(state_->runs, state_->info, api);
    if (response.deferred) {
      stream_.expires_never();  // a batch run may take a while
      auto self = shared_from_this();
      response.deferred([self](ApiResponse ready) {
        net::post(self->stream_.get_executor(), [self, ready = std::move(ready)] { self->send_api(ready); });
      });
      return;
    }
    send_api(response);
  }

  void send_api(const ApiResponse& api) {
    auto response = std::make_shared<http::response<http::string_body>>(http::status(api.status), version_);
    response->set(http::field::server, "rrlab/" + state_->info.version);
    if (!api.content_type.empty()) response->set(http::field::content_type, api.content_type);
    response->set(http::field::cache_control, "no-store");
    for (const auto& [name, value] : access_headers_) response->set(name, value);
    response->keep_alive(keep_alive_);
    response->body() = api.body;
    response->prepare_payload();
    write(response);
  }

  void send_error(int status, const std::string& message) {
    send_api(error_response(ApiError(status, status_code_name(status), message, "")));
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
    if (request.method() == http::verb::head || unchanged) {
      auto response = std::make_shared<http::response<http::empty_body>>(
          unchanged ? http::status::not_modified : http::status::ok, version_);
      response->set(http::field::content_type, file->mime_type);
      response->set(http::field::cache_control, kStaticCacheControl);
      response->set(http::field::etag, file->etag);
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
    response->content_length(size);
    response->keep_alive(keep_alive_);
    write(response);
  }

  // /ws/runs/{id} and /ws/replays/{id}
  void upgrade(http::request<http::string_body>&& request, const std::string& path) {
    std::shared_ptr<FrameSource> source;
    const auto id_after = [&](std::string_view prefix) {
      return path.rfind(prefix, 0) == 0 ? parse_id(std::string_view(path).substr(prefix.size())) : std::nullopt;
    };
    int lane = 0;
    if (const auto run = id_after("/ws/runs/")) {
      if (auto group = state_->runs.group_of(*run, lane)) source = group->source(lane);
    } else if (const auto replay = id_after("/ws/replays/")) {
      source = state_->runs.replay(*replay);
    }
    if (!source) return send_error(404, "no live run or replay at " + path);
    if (state_->websockets.load() >= state_->limits.max_websockets)
      return send_error(503, "too many WebSocket clients");
    double display_hz = state_->runs.limits().default_display_hz;
    start_websocket_session(std::move(stream_), state_, std::move(source), std::move(request), display_hz);
  }

  template <typename Response>
  void write(std::shared_ptr<Response> response) {
    stream_.expires_after(state_->limits.read_timeout);
    http::async_write(stream_, *response, [self = shared_from_this(), response](beast::error_code ec, std::size_t) {
      if (ec) return;
      if (self->drain_after_write_) return self->drain();
      if (!self->keep_alive_) return self->close();
      self->read();
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
