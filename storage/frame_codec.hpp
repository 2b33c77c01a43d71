// Frames as stored: every deterministic field of a Frame packed into one blob
// of little-endian numbers, so that a re-simulated frame can be compared with
// the stored one byte for byte. Compute time (step_us) and overlays are not
// deterministic data and are not stored.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "sim/frame.hpp"
#include "storage/run_store.hpp"

namespace rrlab::storage {

// Layout: u32 n, u32 k, i64 step, then doubles t, q[n], qdot[n], ee[3],
// ee_quat[4] (w x y z), target[3], task_error, orientation_error,
// min_distance, min_distance_link, collided, joint_limit_margin,
// manipulability, condition_number, diagnostics[k].
void pack_frame(const Frame& frame, std::string& out);
std::string pack_frame(const Frame& frame);

// The row stored for the run's frame `seq`; `packed` is pack_frame(frame).
StoredFrame stored_frame(std::int64_t seq, const Frame& frame, std::string packed);

// Throws std::runtime_error on a blob that is not a packed frame.
Frame unpack_frame(std::string_view blob);

// One frame as JSON: {step, t, q, qdot, ee, ee_quat, target, metrics..., diagnostics{}}.
// Non-finite numbers become null.
nlohmann::json frame_to_json(const Frame& frame, const std::vector<std::string>& diagnostic_names);

}  // namespace rrlab::storage
