// GET /api/runs/{id}/drawn: stored frames as a replay draws them, for a page
// that scrubs from its own memory (web/js/local_frames.js) instead of asking
// a replay player for every frame. Newline-delimited JSON, streamed like a
// frame export (a BodyStream produced on an export worker):
//   {"type":"drawn","run","from","to","stride","frames"}   (frames: all the run stored)
// then for each frame, in seq order, the scene when it differs from the
// previous line's (and before the first frame):
//   {"type":"scene","run","scene_version","obstacles":[..],"seq","method"}  (a scene message, with seq and method)
// and the frame itself, byte for byte what the replay player would send for
// it (app/stream_json.hpp encode_frame, status "paused"; scene_version counts
// this response's scenes only). Memory is one batch of stored frames.
#pragma once

#include <cstdint>
#include <memory>

#include <rrlab/server/api/response.hpp>
#include <rrlab/storage/run_store.hpp>

namespace rrlab::server {

// Frames one request may ask for: a page asks again from the next.
inline constexpr std::int64_t kDrawnFramesPerRequest = 2000;

// Frames from..to (clamped to the stored ones and to kDrawnFramesPerRequest
// at `stride`), every stride-th from `from`. Throws DomainError: wrong_state
// when the run has no stored frames or its scenario no longer loads.
std::shared_ptr<BodyStream> make_drawn_frames(storage::RunStore& store, const storage::RunRecord& run,
                                              std::int64_t from, std::int64_t to, std::int64_t stride);

}  // namespace rrlab::server
