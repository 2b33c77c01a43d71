// A small Beast client for tests and load benchmarks: HTTP requests and
// WebSocket connections to 127.0.0.1, every wait bounded by a timeout.
#pragma once

#include <chrono>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace rrlab::testing {

struct HttpResult {
  int status = 0;
  std::string body, content_type;
  std::map<std::string, std::string> headers;  // every response header, names in lower case
  nlohmann::json json() const { return nlohmann::json::parse(body); }
};

HttpResult http(unsigned short port, const std::string& method, const std::string& target,
                const std::string& body = "", const std::string& accept = "",
                const std::map<std::string, std::string>& request_headers = {});
// As http(), from `local_address` (another loopback address such as
// 127.0.0.2: the server counts it as another client); "" as http().
HttpResult http_from(const std::string& local_address, unsigned short port, const std::string& method,
                     const std::string& target, const std::string& body = "", const std::string& accept = "",
                     const std::map<std::string, std::string>& request_headers = {});
inline HttpResult http_json(unsigned short port, const std::string& method, const std::string& target,
                            const nlohmann::json& body) {
  return http(port, method, target, body.dump());
}

// The status of a WebSocket upgrade's answer (101 when accepted) and its body.
HttpResult ws_upgrade(unsigned short port, const std::string& target,
                      const std::map<std::string, std::string>& headers = {});

class WsClient {
 public:
  // Connects and upgrades (with these extra request headers); throws on failure.
  WsClient(unsigned short port, const std::string& target, const std::map<std::string, std::string>& headers = {});
  ~WsClient();
  // The next text message, or nothing within the timeout.
  std::optional<std::string> read(std::chrono::milliseconds timeout = std::chrono::milliseconds(5000));
  std::optional<nlohmann::json> read_json(std::chrono::milliseconds timeout = std::chrono::milliseconds(5000));
  // The next message of this type, skipping others.
  std::optional<nlohmann::json> read_type(const std::string& type,
                                          std::chrono::milliseconds timeout = std::chrono::milliseconds(5000));
  void send(const std::string& text);
  bool open() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rrlab::testing
