// POST /api/runs/{id}/control on a paused live run (paused again, or a fresh run, after each input).
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rrlab::fuzz::Server::get().live_call("POST", "/control", rrlab::fuzz::as_text(data, size));
  return 0;
}
