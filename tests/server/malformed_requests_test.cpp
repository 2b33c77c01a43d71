// Requests the parser refuses or that are over a limit get an answer before
// the connection closes (400 malformed, 414 URL, 431 header, 413 body), never
// a silent close or a reset; `Expect: 100-continue` is answered at once.
// Raw TCP: these are bytes no HTTP client library would send.
#include <iostream>

#include "raw_connection.hpp"
#include "server_fixture.hpp"

namespace rrlab::testing {
namespace {

using nlohmann::json;
using std::chrono::milliseconds;

class MalformedRequests : public ServerTest {
 protected:
  // Sends `bytes` on a new connection and returns the whole answer (the
  // server closes after a refusal).
  static std::string exchange(const std::string& bytes, bool expect_close = true) {
    RawConnection connection(port());
    connection.write(bytes);
    if (expect_close) {
      EXPECT_TRUE(connection.read_until_closed(milliseconds(5000))) << "the connection stayed open";
      return connection.received();
    }
    return connection.read_until("\r\n\r\n");
  }
  // What the Host header must name: this server and its port (net/request_guard).
  static std::string authority() { return "127.0.0.1:" + std::to_string(port()); }
  // The JSON error of a raw answer.
  static json error_in(const std::string& response) {
    const auto body = response.find("\r\n\r\n");
    if (body == std::string::npos) return {};
    return json::parse(response.substr(body + 4), nullptr, false).value("error", json());
  }
};

TEST_F(MalformedRequests, ABadRequestLineAnswers400ThenCloses) {
  const std::string response = exchange("this is not http\r\n\r\n");
  EXPECT_EQ(status_of(response), 400) << response;
  EXPECT_EQ(error_in(response)["code"], "malformed_request") << response;
}

TEST_F(MalformedRequests, ABareLineFeedAnswers400AtOnce) {
  // Beast would wait for a "\r\n\r\n" until the read timeout
  const auto start = std::chrono::steady_clock::now();
  const std::string response = exchange("GET /api/health HTTP/1.1\nHost: " + authority() + "\n\n");
  EXPECT_EQ(status_of(response), 400) << response;
  EXPECT_NE(error_in(response)["message"].get<std::string>().find("bare LF"), std::string::npos) << response;
  EXPECT_LT(std::chrono::steady_clock::now() - start, milliseconds(15000));  // not the 30 s read timeout
}

TEST_F(MalformedRequests, ANulByteInAHeaderAnswers400) {
  const std::string request = std::string("GET /api/health HTTP/1.1\r\nHost: " + authority() + "\r\nX-Odd: a") + '\0' +
                              "b\r\n\r\n";
  const std::string response = exchange(request);
  EXPECT_EQ(status_of(response), 400) << response;
}

TEST_F(MalformedRequests, ABadChunkSizeAnswers400) {
  const std::string response = exchange(
      "POST /api/scenarios/validate HTTP/1.1\r\nHost: " + authority() + "\r\nTransfer-Encoding: chunked\r\n\r\n"
      "zz\r\n{}\r\n0\r\n\r\n");
  EXPECT_EQ(status_of(response), 400) << response;
}

TEST_F(MalformedRequests, ARequestCutShortAnswers400) {
  RawConnection connection(port());
  connection.write("GET /api/health HTTP/1.1\r\nHost: loc");
  connection.finish_writing();
  EXPECT_TRUE(connection.read_until_closed());
  EXPECT_EQ(status_of(connection.received()), 400) << connection.received();
}

TEST_F(MalformedRequests, AOneMegabyteHeaderAnswers431) {
  const std::string response =
      exchange("GET /api/health HTTP/1.1\r\nHost: " + authority() + "\r\nX-Big: " + std::string(1 << 20, 'a') + "\r\n\r\n");
  EXPECT_EQ(status_of(response), 431) << response.substr(0, 200);
  EXPECT_EQ(error_in(response)["code"], "header_too_large");
}

TEST_F(MalformedRequests, AHundredKilobyteUrlAnswers414) {
  const std::string response =
      exchange("GET /api/health?x=" + std::string(100 << 10, 'a') + " HTTP/1.1\r\nHost: " + authority() + "\r\n\r\n");
  EXPECT_EQ(status_of(response), 414) << response.substr(0, 200);
  EXPECT_EQ(error_in(response)["code"], "url_too_long");
}

TEST_F(MalformedRequests, AUrlOverEightKibWithinTheHeaderLimitAnswers414) {
  const std::string response =
      exchange("GET /api/health?x=" + std::string(9 << 10, 'a') + " HTTP/1.1\r\nHost: " + authority() + "\r\n\r\n");
  EXPECT_EQ(status_of(response), 414) << response.substr(0, 200);
}

TEST_F(MalformedRequests, HeadersAndUrlsUnderTheLimitsAreServed) {
  const std::string response =
      exchange("GET /api/health?x=" + std::string(7 << 10, 'a') + " HTTP/1.1\r\nHost: " + authority() + "\r\nX-Big: " +
                   std::string(7 << 10, 'b') + "\r\n\r\n",
               false);
  EXPECT_EQ(status_of(response), 200) << response.substr(0, 200);
}

TEST_F(MalformedRequests, PipelinedRequestsAreAllAnswered) {
  RawConnection connection(port());
  const std::string one = "GET /api/health HTTP/1.1\r\nHost: " + authority() + "\r\n\r\n";
  connection.write(one + one + "GET /api/health HTTP/1.1\r\nHost: " + authority() + "\r\nConnection: close\r\n\r\n");
  EXPECT_TRUE(connection.read_until_closed());
  std::size_t answers = 0;
  for (auto at = connection.received().find("HTTP/1.1 200"); at != std::string::npos;
       at = connection.received().find("HTTP/1.1 200", at + 1))
    ++answers;
  EXPECT_EQ(answers, 3u) << connection.received();
}

// The 100 Continue comes before the client sends its body (curl would wait
// 1 s for it otherwise): the client here sends nothing until it has it.
TEST_F(MalformedRequests, ExpectContinueGets100BeforeTheBodyThenTheAnswer) {
  const std::string body = small_scenario("circle", 2.0).dump();
  RawConnection connection(port());
  const auto start = std::chrono::steady_clock::now();
  connection.write("POST /api/scenarios/validate HTTP/1.1\r\nHost: " + authority() + "\r\nContent-Type: application/json\r\n"
                   "Content-Length: " + std::to_string(body.size()) + "\r\nExpect: 100-continue\r\n\r\n");
  const std::string interim = connection.read_until("\r\n\r\n", milliseconds(10000));
  std::cout << "100 Continue after "
            << std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() << " ms\n";
  ASSERT_EQ(interim.rfind("HTTP/1.1 100 Continue\r\n\r\n", 0), 0u) << interim;

  connection.write(body);
  const std::string response = connection.read_until("\"valid\"", milliseconds(5000));
  EXPECT_EQ(status_of(response.substr(interim.size())), 200) << response;
}

TEST_F(MalformedRequests, ExpectContinueOverTheBodyLimitGets413AtOnce) {
  RawConnection connection(port());
  connection.write("POST /api/scenarios/validate HTTP/1.1\r\nHost: " + authority() + "\r\nContent-Length: " +
                   std::to_string(2 << 20) + "\r\nExpect: 100-continue\r\n\r\n");
  const std::string response = connection.read_until("\r\n\r\n", milliseconds(1000));
  EXPECT_EQ(status_of(response), 413) << response;
}

}  // namespace
}  // namespace rrlab::testing
