// POST /api/scenarios/validate and, for what it accepts, POST /api/scenarios
// (stored in the fuzzer's temporary database).
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  auto& server = rrlab::fuzz::Server::get();
  const std::string body = rrlab::fuzz::as_text(data, size);
  if (server.idle_call("POST", "/api/scenarios/validate", body).status == 200)
    server.idle_call("POST", "/api/scenarios", body);
  return 0;
}
