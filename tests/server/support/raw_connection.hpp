// A plain TCP connection to 127.0.0.1 for tests that send bytes no HTTP
// client would (malformed request lines, bare LFs, oversized headers,
// repeated headers): write raw bytes, read what comes back, every wait
// bounded by a timeout. It may come from another loopback address
// (127.0.0.2, ...: loopback on Linux), as a client on another machine would.
#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <stdexcept>
#include <string>

namespace rrlab::testing {

class RawConnection {
 public:
  using Clock = std::chrono::steady_clock;

  // `receive_buffer` > 0: SO_RCVBUF before connecting (a client that reads
  // nothing then takes little of an answer into its kernel buffer).
  // `from`: the local IPv4 address to connect from (a loopback one), "" any.
  explicit RawConnection(unsigned short port, int receive_buffer = 0, const std::string& from = "")
      : fd_(::socket(AF_INET, SOCK_STREAM, 0)) {
    if (fd_ < 0) throw std::runtime_error("socket() failed");
    if (receive_buffer > 0) ::setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &receive_buffer, sizeof receive_buffer);
    if (!from.empty()) bind_to(from);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(port);
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::connect(fd_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
      ::close(fd_);
      throw std::runtime_error("connect() failed");
    }
  }
  ~RawConnection() { ::close(fd_); }
  RawConnection(const RawConnection&) = delete;
  RawConnection& operator=(const RawConnection&) = delete;

  // Writes as much of `bytes` as the server takes; false when it stopped
  // taking them (closed or reset), which tests of refusals expect.
  bool write(const std::string& bytes, std::chrono::milliseconds timeout = std::chrono::milliseconds(5000)) {
    const auto deadline = Clock::now() + timeout;
    std::size_t sent = 0;
    while (sent < bytes.size()) {
      if (!wait_for(POLLOUT, deadline)) return false;
      const ssize_t n = ::send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL | MSG_DONTWAIT);
      if (n <= 0) return false;
      sent += std::size_t(n);
    }
    return true;
  }

  // Half-closes: the server reads the end of the stream, and can still answer.
  void finish_writing() { ::shutdown(fd_, SHUT_WR); }

  // Reads until `marker` has arrived (returns everything read), the server
  // closes, or the timeout passes.
  std::string read_until(const std::string& marker,
                         std::chrono::milliseconds timeout = std::chrono::milliseconds(5000)) {
    const auto deadline = Clock::now() + timeout;
    while (received_.find(marker) == std::string::npos && read_some(deadline)) {
    }
    return received_;
  }

  // Reads until the server closes (true) or the timeout passes (false).
  bool read_until_closed(std::chrono::milliseconds timeout = std::chrono::milliseconds(5000)) {
    const auto deadline = Clock::now() + timeout;
    while (read_some(deadline)) {
    }
    return closed_;
  }

  const std::string& received() const { return received_; }

 private:
  void bind_to(const std::string& from) {
    sockaddr_in local{};
    local.sin_family = AF_INET;
    if (::inet_pton(AF_INET, from.c_str(), &local.sin_addr) != 1 ||
        ::bind(fd_, reinterpret_cast<sockaddr*>(&local), sizeof local) != 0) {
      ::close(fd_);
      throw std::runtime_error("cannot bind to " + from);
    }
  }

  bool wait_for(short events, Clock::time_point deadline) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0) return false;
    pollfd p{fd_, events, 0};
    return ::poll(&p, 1, int(left)) > 0;
  }

  // One read; false at the end (closed, reset or timed out).
  bool read_some(Clock::time_point deadline) {
    if (closed_ || !wait_for(POLLIN, deadline)) return false;
    char buffer[65536];
    const ssize_t n = ::recv(fd_, buffer, sizeof buffer, MSG_DONTWAIT);
    if (n <= 0) {
      closed_ = true;
      return false;
    }
    received_.append(buffer, std::size_t(n));
    return true;
  }

  int fd_;
  std::string received_;
  bool closed_ = false;
};

// A WebSocket upgrade request for `target` as a browser would send it, with
// `extra` header lines ("Name: value\r\n" each) before the blank line.
inline std::string websocket_upgrade_request(unsigned short port, const std::string& target,
                                             const std::string& extra = "") {
  return "GET " + target + " HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port) +
         "\r\nUpgrade: websocket\r\nConnection: Upgrade\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n"
         "Sec-WebSocket-Version: 13\r\n" +
         extra + "\r\n";
}

// The status line's code ("HTTP/1.1 431 ..." -> 431), 0 when there is none.
inline int status_of(const std::string& response) {
  if (response.rfind("HTTP/1.", 0) != 0 || response.size() < 12) return 0;
  return std::stoi(response.substr(9, 3));
}

}  // namespace rrlab::testing
