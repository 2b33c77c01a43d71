// POST /api/runs/{id}/joystick on a paused live run.
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rrlab::fuzz::Server::get().live_call("POST", "/joystick", rrlab::fuzz::as_text(data, size));
  return 0;
}
