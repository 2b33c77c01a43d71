// PATCH /api/runs/{id}/params on a paused live run.
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rrlab::fuzz::Server::get().live_call("PATCH", "/params", rrlab::fuzz::as_text(data, size));
  return 0;
}
