#include "client.hpp"

#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <cctype>
#include <stdexcept>

namespace rrlab::testing {

namespace beast = boost::beast;
namespace http_ns = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;
using tcp = net::ip::tcp;

HttpResult http(unsigned short port, const std::string& method, const std::string& target, const std::string& body,
                const std::string& accept, const std::map<std::string, std::string>& request_headers) {
  return http_from("", port, method, target, body, accept, request_headers);
}

HttpResult http_from(const std::string& local_address, unsigned short port, const std::string& method,
                     const std::string& target, const std::string& body, const std::string& accept,
                     const std::map<std::string, std::string>& request_headers) {
  net::io_context ioc;
  beast::tcp_stream stream(ioc);
  stream.expires_after(std::chrono::seconds(120));
  if (!local_address.empty()) {  // another loopback address: the server sees another client
    stream.socket().open(tcp::v4());
    stream.socket().bind(tcp::endpoint(net::ip::make_address(local_address), 0));
  }
  stream.connect(tcp::endpoint(net::ip::make_address("127.0.0.1"), port));
  http_ns::request<http_ns::string_body> request(http_ns::string_to_verb(method), target, 11);
  request.set(http_ns::field::host, "127.0.0.1:" + std::to_string(port));  // the server checks Host
  if (!body.empty()) request.set(http_ns::field::content_type, "application/json");
  if (!accept.empty()) request.set(http_ns::field::accept, accept);
  for (const auto& [name, value] : request_headers) request.set(name, value);
  request.body() = body;
  request.prepare_payload();
  request.keep_alive(false);
  HttpResult result;
  beast::flat_buffer buffer;
  http_ns::response_parser<http_ns::string_body> parser;
  parser.body_limit(1ull << 30);
  if (method == "HEAD") parser.skip(true);  // a HEAD answer has a Content-Length but no body
  beast::error_code error;
  // read the answer even when the write failed: a server may refuse a body midway (413)
  http_ns::async_write(stream, request, [&](beast::error_code, std::size_t) {
    http_ns::async_read(stream, buffer, parser, [&](beast::error_code ec2, std::size_t) { error = ec2; });
  });
  ioc.run();
  // a server may answer (e.g. 413) and close before reading the whole body
  if (error && !parser.is_header_done()) throw std::runtime_error("http " + method + " " + target + ": " + error.message());
  auto response = parser.release();
  result.status = int(response.result_int());
  result.body = response.body();
  result.content_type = std::string(response[http_ns::field::content_type]);
  for (const auto& field : response) {
    std::string name(field.name_string());
    for (char& ch : name) ch = char(std::tolower(static_cast<unsigned char>(ch)));
    result.headers[name] = std::string(field.value());
  }
  return result;
}

struct WsClient::Impl {
  net::io_context ioc;
  websocket::stream<beast::tcp_stream> ws{ioc};
  beast::flat_buffer buffer;
  bool open = false;
};

namespace {
// Connects and upgrades; the handshake's error, the answer in `response`.
beast::error_code handshake(net::io_context& ioc, websocket::stream<beast::tcp_stream>& ws, unsigned short port,
                            const std::string& target, const std::map<std::string, std::string>& headers,
                            websocket::response_type& response) {
  auto& lowest = beast::get_lowest_layer(ws);
  lowest.expires_after(std::chrono::seconds(10));
  lowest.connect(tcp::endpoint(net::ip::make_address("127.0.0.1"), port));
  ws.set_option(websocket::stream_base::decorator([headers](websocket::request_type& request) {
    for (const auto& [name, value] : headers) request.set(name, value);
  }));
  beast::error_code error;
  ws.async_handshake(response, "127.0.0.1:" + std::to_string(port), target, [&](beast::error_code ec) { error = ec; });
  ioc.run();
  return error;
}
}  // namespace

HttpResult ws_upgrade(unsigned short port, const std::string& target, const std::map<std::string, std::string>& headers) {
  net::io_context ioc;
  websocket::stream<beast::tcp_stream> ws(ioc);
  websocket::response_type response;
  handshake(ioc, ws, port, target, headers, response);
  HttpResult result;
  result.status = int(response.result_int());
  result.body = response.body();
  result.content_type = std::string(response[http_ns::field::content_type]);
  beast::error_code ec;
  beast::get_lowest_layer(ws).socket().close(ec);
  return result;
}

WsClient::WsClient(unsigned short port, const std::string& target, const std::map<std::string, std::string>& headers)
    : impl_(std::make_unique<Impl>()) {
  auto& lowest = beast::get_lowest_layer(impl_->ws);
  websocket::response_type response;
  const beast::error_code error = handshake(impl_->ioc, impl_->ws, port, target, headers, response);
  if (error) throw std::runtime_error("websocket " + target + ": " + error.message());
  lowest.expires_never();
  impl_->open = true;
}

WsClient::~WsClient() {
  beast::error_code ec;
  beast::get_lowest_layer(impl_->ws).socket().close(ec);
}

bool WsClient::open() const { return impl_->open; }

std::optional<std::string> WsClient::read(std::chrono::milliseconds timeout) {
  if (!impl_->open) return std::nullopt;
  bool done = false;
  beast::error_code error;
  impl_->ws.async_read(impl_->buffer, [&](beast::error_code ec, std::size_t) {
    error = ec;
    done = true;
  });
  impl_->ioc.restart();
  impl_->ioc.run_for(timeout);
  if (!done) {
    // give up: the connection cannot be read again after a cancelled read
    beast::error_code ec;
    beast::get_lowest_layer(impl_->ws).socket().cancel(ec);
    impl_->ioc.restart();
    impl_->ioc.run();
    impl_->open = false;
    return std::nullopt;
  }
  if (error) {
    impl_->open = false;
    return std::nullopt;
  }
  std::string text = beast::buffers_to_string(impl_->buffer.data());
  impl_->buffer.consume(impl_->buffer.size());
  return text;
}

std::optional<nlohmann::json> WsClient::read_json(std::chrono::milliseconds timeout) {
  auto text = read(timeout);
  if (!text) return std::nullopt;
  return nlohmann::json::parse(*text);
}

std::optional<nlohmann::json> WsClient::read_type(const std::string& type, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    auto message = read_json(left);
    if (!message) return std::nullopt;
    if (message->value("type", "") == type) return message;
  }
  return std::nullopt;
}

void WsClient::send(const std::string& text) {
  beast::error_code error;
  impl_->ws.async_write(net::buffer(text), [&](beast::error_code ec, std::size_t) { error = ec; });
  impl_->ioc.restart();
  impl_->ioc.run();
  if (error) throw std::runtime_error("websocket send: " + error.message());
}

}  // namespace rrlab::testing
