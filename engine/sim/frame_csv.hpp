// The frame CSV, shared by `rrlab run --out` (a live frame, with step_us) and
// the frames export (a stored frame): one column per number of the fields of
// kFrameFields (sim/frame_fields.hpp) that CSV carries, in its order. A field
// of several numbers has one column each: q1..qn, ee_x ee_y ee_z, ee_quat_w
// ee_quat_x ee_quat_y ee_quat_z; the diagnostics are named by the method.
#pragma once

#include <string>
#include <vector>

#include <rrlab/sim/frame_fields.hpp>

namespace rrlab {

std::string frame_csv_header(int dof, const std::vector<std::string>& diagnostic_names, FrameOrigin origin);
// Appends one row (with its newline); numbers in their shortest exact form, inf/NaN empty.
void append_frame_csv(const Frame& frame, FrameOrigin origin, std::string& out);

}  // namespace rrlab
