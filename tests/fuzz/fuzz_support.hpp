// Shared by the libFuzzer targets of tests/fuzz/: what counts as a finding,
// and an in-process server (RunManager on a temporary database) whose REST
// routes and WebSocket message handler take the fuzzer's bytes as a body.
//
// A documented error (ScenarioError, ParamError, InputStateError, DomainError,
// a JSON parse error; over REST any 4xx or 503) is the right answer to bad
// input. Anything else is a finding: another exception escaping a parser, or
// a 500 answer (an exception the route did not expect), aborts with the
// input's reply, and so do crashes, sanitizer reports, leaks and timeouts.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include <rrlab/server/api/request.hpp>
#include <rrlab/server/api/response.hpp>

namespace rrlab::fuzz {

std::string as_text(const std::uint8_t* data, std::size_t size);

// Runs `parse`; documented errors are fine, any other exception aborts.
void expect_documented(const std::string& what, const std::function<void()>& parse);

// An in-process server: `idle` refuses to start anything (no run, no sweep:
// every request is parsed and validated, then answered 503), `live` has one
// paused live run (run_id) that inputs go to.
class Server {
 public:
  static Server& get();  // one per process, made on first use

  // The route's answer; aborts on a 5xx other than 503.
  server::ApiResponse idle_call(const std::string& method, const std::string& path, const std::string& body);
  server::ApiResponse live_call(const std::string& method, const std::string& path_after_run,
                                const std::string& body);
  // The live run's WebSocket reply to `text` (aborts on an "internal" error).
  nlohmann::json live_message(const std::string& text);

 private:
  Server();
  struct State;
  void fresh_run();
  void after_input();
  std::unique_ptr<State> state_;
};

}  // namespace rrlab::fuzz
