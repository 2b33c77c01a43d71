// One WebSocket client of a live run or replay. A timer at the display rate
// sends the latest published frame if the previous write has completed
// (latest wins: a slow client skips frames and never holds up the run or the
// other clients); a write pending longer than the stall timeout drops the
// client. Replies to the client's messages go first, one write in flight.
// Messages steer only from a client with the token (when the server has one)
// that holds control of the run (app/controller.hpp).
#include <atomic>
#include <deque>

#include <rrlab/server/app/controller.hpp>
#include <rrlab/server/routes/socket_message.hpp>
#include <rrlab/server/net/sessions.hpp>

namespace rrlab::server {

namespace {

using Clock = std::chrono::steady_clock;

class WebSocketSession : public std::enable_shared_from_this<WebSocketSession> {
 public:
  WebSocketSession(beast::tcp_stream&& stream, std::shared_ptr<ServerState> state,
                   std::shared_ptr<FrameSource> source, double display_hz, WebSocketClient client,
                   std::array<PeerLimits::Hold, 2> holds)
      : client_(std::move(client)),
        ws_(std::move(stream)),
        state_(std::move(state)),
        holds_(std::move(holds)),
        source_(std::move(source)),
        tick_(ws_.get_executor()),
        period_(std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / display_hz))) {
    ++state_->websockets;
  }
  ~WebSocketSession() {
    if (subscription_) source_->subscribers().remove(subscription_);
    if (controller_connection_) source_->controller()->detach(controller_connection_);
    --state_->websockets;
  }

  void run(http::request<http::string_body>&& request) {
    beast::get_lowest_layer(ws_).expires_never();  // the WebSocket has its own timeouts
    // a small kernel send queue: a slow client holds a few frames, not seconds of them
    beast::error_code ec;
    beast::get_lowest_layer(ws_).socket().set_option(net::socket_base::send_buffer_size(64 * 1024), ec);
    ws_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
    ws_.set_option(websocket::stream_base::decorator(
        [](websocket::response_type& res) { res.set(http::field::server, "rrlab"); }));
    ws_.read_message_max(state_->limits.ws_message_limit);
    ws_.async_accept(request, [self = shared_from_this()](beast::error_code ec) {
      if (ec) return;
      self->open_ = true;
      self->attach_controller();
      // new frames are pushed at once: the publisher posts onto this strand.
      // Subscribed before the snapshot is written: a client that has read its
      // snapshot is counted as watching (the snapshot's write may complete
      // before this handler returns, and the client act on it at once).
      std::weak_ptr<WebSocketSession> weak = self;
      self->subscription_ = self->source_->subscribers().add([weak] {
        if (auto session = weak.lock())
          net::post(session->ws_.get_executor(), [session] { session->send_latest(); });
      });
      self->send_snapshot();
      self->read();
      self->arm_timer();
    });
  }

 private:
  // A client of a live run hears when another client takes control from it.
  // Without a `client` name the connection is a client of its own ('#' is
  // not allowed in names, so this one is nobody else's).
  void attach_controller() {
    Controller* controller = source_->controller();
    if (!controller) return;
    static std::atomic<std::uint64_t> connections{0};
    if (client_.name.empty()) client_.name = "#" + std::to_string(++connections);
    std::weak_ptr<WebSocketSession> weak = shared_from_this();
    controller_connection_ = controller->attach(client_.name, [weak](const nlohmann::json& message) {
      if (auto session = weak.lock()) {
        auto text = std::make_shared<const std::string>(safe_dump(message));
        net::post(session->ws_.get_executor(), [session, text] {
          if (session->open_) session->queue(text);
        });
      }
    });
  }

  void send_snapshot() {
    const PublishedFrame latest = source_->latest();
    sent_version_ = latest.version;
    sent_scene_ = latest.scene_version;
    queue(std::make_shared<const std::string>(source_->snapshot()));
  }

  // What changed since the scene this client has: a parameter change or an
  // obstacle moved is a small message, anything else a new snapshot.
  void send_scene_update() {
    SceneUpdate update = source_->update_since(sent_scene_);
    sent_scene_ = update.version;
    for (std::string& message : update.messages) queue(std::make_shared<const std::string>(std::move(message)));
  }

  void queue(std::shared_ptr<const std::string> message) {
    if (replies_.size() >= 64) return close();  // a client that floods without reading
    replies_.push_back(std::move(message));
    if (!writing_) write_next();
  }

  void arm_timer() {
    tick_.expires_after(period_);
    tick_.async_wait([self = shared_from_this()](beast::error_code ec) {
      if (ec || !self->open_) return;
      self->on_tick();
      self->arm_timer();
    });
  }

  // The timer: drops a stalled client, and sends what a notification missed.
  void on_tick() {
    if (writing_) {
      if (Clock::now() - write_started_ > state_->limits.ws_stall_timeout) close();
      return;
    }
    send_latest();
  }

  // Latest wins: while a write is in flight nothing is queued; the newest
  // frame goes out when it completes, frames published meanwhile are skipped.
  void send_latest() {
    if (!open_ || writing_) return;
    const PublishedFrame latest = source_->latest();
    if (latest.scene_version > sent_scene_) return send_scene_update();
    if (latest.version == sent_version_ || !latest.text) return;
    sent_version_ = latest.version;
    start_write(latest.text);
  }

  void write_next() {
    if (replies_.empty()) return;
    auto message = replies_.front();
    replies_.pop_front();
    start_write(std::move(message));
  }

  void start_write(std::shared_ptr<const std::string> message) {
    writing_ = true;
    write_started_ = Clock::now();
    ws_.text(true);
    ws_.async_write(net::buffer(*message),
                    [self = shared_from_this(), message](beast::error_code ec, std::size_t) {
                      self->writing_ = false;
                      if (ec) return self->close();
                      if (!self->replies_.empty())
                        self->write_next();
                      else
                        self->send_latest();
                    });
  }

  void read() {
    ws_.async_read(buffer_, [self = shared_from_this()](beast::error_code ec, std::size_t) {
      if (ec) return self->close();
      self->on_message();
      self->read();
    });
  }

  // Replies go out in the order of the messages; one that waits (an input
  // until its event is stored, a step until it is taken) holds back the
  // replies after it, and no thread waits meanwhile.
  void on_message() {
    const std::string text = beast::buffers_to_string(buffer_.data());
    buffer_.consume(buffer_.size());
    if (awaiting_.size() >= 64) return close();  // a client that floods without reading
    MessageReply reply = reply_to(text);
    auto slot = std::make_shared<std::shared_ptr<const std::string>>();
    awaiting_.push_back(slot);
    if (!reply.pending) {
      *slot = std::make_shared<const std::string>(safe_dump(reply.reply));
      return send_ready_replies();
    }
    std::weak_ptr<WebSocketSession> weak = shared_from_this();
    // the callback holds the reply's text only: the completion it is stored in is not kept alive by it
    reply.pending->then([weak, slot, ack = std::move(reply.reply)](const storage::Outcome& outcome) {
      auto settled = std::make_shared<const std::string>(safe_dump(settled_reply(ack, outcome)));
      if (auto session = weak.lock())
        net::post(session->ws_.get_executor(), [session, slot, settled] {
          *slot = settled;
          if (session->open_) session->send_ready_replies();
        });
    });
  }

  void send_ready_replies() {
    while (!awaiting_.empty() && *awaiting_.front()) {
      queue(std::move(*awaiting_.front()));
      awaiting_.pop_front();
    }
  }

  // An ack or an error for every message; the socket stays open whatever the
  // client sent (no exception reaches the I/O loop).
  MessageReply reply_to(const std::string& text) {
    if (over_rate_limit())
      return {socket_error(DomainError(Problem::too_many, "rate_limited",
                                       "more than " + std::to_string(state_->limits.ws_messages_per_second) +
                                           " messages per second; this one was dropped")),
              nullptr};
    return reply_to_socket_message(*source_, client_.name, client_.may_steer, text);
  }

  // At most N messages per one-second window.
  bool over_rate_limit() {
    const auto now = Clock::now();
    if (now - window_start_ > std::chrono::seconds(1)) {
      window_start_ = now;
      window_count_ = 0;
    }
    return ++window_count_ > state_->limits.ws_messages_per_second;
  }

  void close() {
    if (!open_) return;
    open_ = false;
    tick_.cancel();
    beast::error_code ec;
    beast::get_lowest_layer(ws_).socket().shutdown(tcp::socket::shutdown_both, ec);
    beast::get_lowest_layer(ws_).socket().close(ec);
  }

  WebSocketClient client_;
  std::uint64_t controller_connection_ = 0;
  websocket::stream<beast::tcp_stream> ws_;
  std::shared_ptr<ServerState> state_;
  std::array<PeerLimits::Hold, 2> holds_;  // after state_ (which owns the limits): released before it
  std::shared_ptr<FrameSource> source_;
  beast::flat_buffer buffer_;
  net::steady_timer tick_;
  Clock::duration period_;
  std::deque<std::shared_ptr<const std::string>> replies_;
  std::deque<std::shared_ptr<std::shared_ptr<const std::string>>> awaiting_;  // replies in message order, null until ready
  bool open_ = false, writing_ = false;
  Clock::time_point write_started_{}, window_start_{};
  int window_count_ = 0;
  std::uint64_t sent_version_ = 0, sent_scene_ = 0;
  std::uint64_t subscription_ = 0;
};

}  // namespace

void start_websocket_session(beast::tcp_stream&& stream, std::shared_ptr<ServerState> state,
                             std::shared_ptr<FrameSource> source, http::request<http::string_body>&& request,
                             double display_hz, WebSocketClient client, std::array<PeerLimits::Hold, 2> holds) {
  std::make_shared<WebSocketSession>(std::move(stream), std::move(state), std::move(source), display_hz,
                                     std::move(client), std::move(holds))
      ->run(std::move(request));
}

}  // namespace rrlab::server
