// Connection classes of the server (Beast's advanced server example shape).
// Included by net/*.cpp only: it brings Beast in.
#pragma once

#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <array>
#include <memory>

#include <rrlab/server/app/frame_source.hpp>
#include <rrlab/server/net/server_state.hpp>

namespace rrlab::server {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;
using tcp = net::ip::tcp;

// Reads HTTP requests on one connection; upgrades to a WebSocket on /ws/...
void start_http_session(tcp::socket&& socket, std::shared_ptr<ServerState> state);

// Who is on a WebSocket: whether its messages may steer (false: a tokenless
// watcher under --public-read) and its client name (app/controller.hpp; empty: unnamed).
struct WebSocketClient {
  bool may_steer = true;
  std::string name;
};

// Takes over an upgraded connection and streams `source` to it; `holds`: its
// places among the peer limits (the connection's and the WebSocket's), kept while it lives.
void start_websocket_session(beast::tcp_stream&& stream, std::shared_ptr<ServerState> state,
                             std::shared_ptr<FrameSource> source, http::request<http::string_body>&& request,
                             double display_hz, WebSocketClient client, std::array<PeerLimits::Hold, 2> holds);

// Accepts connections on host:port (0: ephemeral); returns the bound port.
unsigned short start_listener(net::io_context& ioc, const std::string& host, unsigned short port,
                              std::shared_ptr<ServerState> state);

}  // namespace rrlab::server
