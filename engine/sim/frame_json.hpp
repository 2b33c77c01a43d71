// A frame as JSON, one shape for the WebSocket stream and for stored frames
// (GET /api/runs/{id}/frames): the fields of kFrameFields (sim/frame_fields.hpp)
// in its order, the metrics inside "metrics", the diagnostics an array in the
// order of the run's diagnostic_names.
#pragma once

#include <string>

#include <rrlab/sim/frame_fields.hpp>

namespace rrlab {

// The frame's members, without braces: "step":..,"t":..,"q":[..],..,
// "metrics":{"task_error":..,..},"diagnostics":[..]. digits 0: exact values
// (the shortest text that reads back to the same double); else that many
// significant digits (the stream draws with 7). Non-finite numbers are null.
void append_frame_json_members(const Frame& frame, FrameOrigin origin, int digits, std::string& out);

}  // namespace rrlab
