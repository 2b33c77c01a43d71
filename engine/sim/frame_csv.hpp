// The frame CSV (the `--out` columns of docs/cli.md), shared by `rrlab run --out` and the frames export:
// step,t,q1..qn,qdot1..qdotn,ee_x,ee_y,ee_z,task_error,min_distance,collided,
// then orientation_error, min_distance_link (1-based, 0: none), joint_limit_margin,
// manipulability, condition_number, the method's diagnostics and, when asked, step_us.
#pragma once

#include <string>
#include <vector>

#include "sim/frame.hpp"

namespace rrlab {

std::string frame_csv_header(int dof, const std::vector<std::string>& diagnostic_names, bool with_step_us);
// Appends one row (with its newline); numbers in their shortest exact form, inf/NaN empty.
void append_frame_csv(const Frame& frame, bool with_step_us, std::string& out);

}  // namespace rrlab
