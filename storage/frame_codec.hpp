// Frames as stored: every deterministic field of a Frame packed into one blob
// of little-endian numbers, so that a re-simulated frame can be compared with
// the stored one byte for byte. Compute time (step_us) and overlays are not
// deterministic data and are not stored.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <rrlab/sim/frame_fields.hpp>
#include <rrlab/storage/run_store.hpp>

namespace rrlab::storage {

// Layout (version 3, kFrameBlobVersion): u32 version word (0x52460000 |
// version), u32 n (joints), u32 k (diagnostics), then the blob fields of
// kFrameFields (sim/frame_fields.hpp) in its order, the step as an i64 and
// every other number as a double: t, q[n], qdot[n], ee[3], ee_quat[4]
// (w x y z), target[3], task_error, orientation_error, min_distance,
// min_distance_link, collided, min_self_distance, self_link_a, self_link_b,
// self_collided, joint_limit_margin, manipulability, condition_number,
// diagnostics[k]. Version 2 has no self-collision fields (a decoded frame's
// min_self_distance is NaN: unknown); version 1 (runs stored before the
// word existed) starts at n and has version 2's fields. A version's fields
// are the blob fields whose `since` is at most that version.
void pack_frame(const Frame& frame, std::string& out, int version = kFrameBlobVersion);
std::string pack_frame(const Frame& frame);

// The format version of a packed frame (1 to kFrameBlobVersion); throws std::runtime_error
// on a blob too short to say, or of a version this build does not know.
int frame_blob_version(std::string_view blob);

// The row stored for the run's frame `seq`; `packed` is pack_frame(frame).
StoredFrame stored_frame(std::int64_t seq, const Frame& frame, std::string packed);

// Any version this build knows; throws std::runtime_error on a blob that is
// not a packed frame.
Frame unpack_frame(std::string_view blob);

// One stored frame as GET /api/runs/{id}/frames writes it: {"seq":..,
// then the members of sim/frame_json.hpp with exact values}.
void append_stored_frame_json(std::int64_t seq, const Frame& frame, std::string& out);

}  // namespace rrlab::storage
