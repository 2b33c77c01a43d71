// POST /api/runs: the body parsed and validated (scenario, method, params, options), then refused 503 by a server that starts nothing.
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rrlab::fuzz::Server::get().idle_call("POST", "/api/runs", rrlab::fuzz::as_text(data, size));
  return 0;
}
