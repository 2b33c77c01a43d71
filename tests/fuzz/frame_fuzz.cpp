// The frame decoder (storage/frame_codec.hpp): a blob from the database,
// decoded and written as GET /api/runs/{id}/frames writes it (JSON and CSV).
// A blob that is not a packed frame is a std::runtime_error, the decoder's
// documented error; the JSON written must parse, and a decoded frame packed
// again must decode to the same JSON.
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string_view>

#include <rrlab/sim/frame_csv.hpp>
#include <rrlab/storage/frame_codec.hpp>

#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rrlab::Frame frame;
  try {
    frame = rrlab::storage::unpack_frame(std::string_view(reinterpret_cast<const char*>(data), size));
  } catch (const std::runtime_error&) {
    return 0;
  }
  std::string json, again, csv;
  rrlab::storage::append_stored_frame_json(1, frame, json);
  if (!nlohmann::json::accept(json)) std::abort();
  rrlab::storage::append_stored_frame_json(1, rrlab::storage::unpack_frame(rrlab::storage::pack_frame(frame)), again);
  if (again != json) std::abort();
  rrlab::append_frame_csv(frame, rrlab::FrameOrigin::stored, csv);
  return 0;
}
