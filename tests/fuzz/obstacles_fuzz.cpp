// POST /api/runs/{id}/obstacles (an odd-sized body) and PUT
// /api/runs/{id}/obstacles/box (an even-sized one) on a paused live run.
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  auto& server = rrlab::fuzz::Server::get();
  if (size % 2)
    server.live_call("POST", "/obstacles", rrlab::fuzz::as_text(data, size));
  else
    server.live_call("PUT", "/obstacles/box", rrlab::fuzz::as_text(data, size));
  return 0;
}
