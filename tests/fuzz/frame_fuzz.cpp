// The frame decoder (storage/frame_codec.hpp): a blob from the database,
// decoded and turned into the JSON of GET /api/runs/{id}/frames. A blob that
// is not a packed frame is a std::runtime_error, the decoder's documented error.
#include <stdexcept>
#include <string_view>

#include "fuzz_support.hpp"
#include "storage/frame_codec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rrlab::Frame frame;
  try {
    frame = rrlab::storage::unpack_frame(std::string_view(reinterpret_cast<const char*>(data), size));
  } catch (const std::runtime_error&) {
    return 0;
  }
  rrlab::storage::frame_to_json(frame, {"a", "b"}).dump();
  return 0;
}
