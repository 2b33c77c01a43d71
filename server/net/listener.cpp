#include <rrlab/server/net/sessions.hpp>

namespace rrlab::server {

namespace {

class Listener : public std::enable_shared_from_this<Listener> {
 public:
  Listener(net::io_context& ioc, tcp::endpoint endpoint, std::shared_ptr<ServerState> state)
      : ioc_(ioc), acceptor_(net::make_strand(ioc)), state_(std::move(state)) {
    acceptor_.open(endpoint.protocol());
    acceptor_.set_option(net::socket_base::reuse_address(true));
    acceptor_.bind(endpoint);
    acceptor_.listen(net::socket_base::max_listen_connections);
  }
  unsigned short port() const { return acceptor_.local_endpoint().port(); }
  void run() { accept(); }

 private:
  void accept() {
    // each connection gets its own strand
    acceptor_.async_accept(net::make_strand(ioc_), [self = shared_from_this()](beast::error_code ec, tcp::socket socket) {
      if (ec == net::error::operation_aborted) return;
      if (ec) {
        // e.g. out of file descriptors: back off instead of spinning
        self->backoff_.expires_after(std::chrono::milliseconds(100));
        self->backoff_.async_wait([self](beast::error_code) { self->accept(); });
        return;
      }
      {
        // frames are small and latency matters: no Nagle delay behind unacknowledged data
        beast::error_code ignored;
        socket.set_option(tcp::no_delay(true), ignored);
        start_http_session(std::move(socket), self->state_);
      }
      self->accept();
    });
  }

  net::io_context& ioc_;
  tcp::acceptor acceptor_;
  net::steady_timer backoff_{acceptor_.get_executor()};
  std::shared_ptr<ServerState> state_;
};

}  // namespace

unsigned short start_listener(net::io_context& ioc, const std::string& host, unsigned short port,
                              std::shared_ptr<ServerState> state) {
  const auto address = net::ip::make_address(host);
  auto listener = std::make_shared<Listener>(ioc, tcp::endpoint(address, port), std::move(state));
  listener->run();
  return listener->port();
}

}  // namespace rrlab::server
