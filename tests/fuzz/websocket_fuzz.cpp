// The WebSocket message handler (app/socket_message.hpp) of a paused live run:
// inputs and controls as a client sends them; an "internal" error is a finding.
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rrlab::fuzz::Server::get().live_message(rrlab::fuzz::as_text(data, size));
  return 0;
}
