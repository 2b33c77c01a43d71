#include "sim/frame_csv.hpp"

#include <charconv>
#include <cmath>

namespace rrlab {

namespace {
// Shortest text that reads back to the same double; empty for inf/NaN.
void number(double v, std::string& out) {
  out += ',';
  if (!std::isfinite(v)) return;
  char buf[32];
  const auto result = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, size_t(result.ptr - buf));
}
}  // namespace

std::string frame_csv_header(int dof, const std::vector<std::string>& diagnostic_names, bool with_step_us) {
  std::string h = "step,t";
  for (int i = 1; i <= dof; ++i) h += ",q" + std::to_string(i);
  for (int i = 1; i <= dof; ++i) h += ",qdot" + std::to_string(i);
  h += ",ee_x,ee_y,ee_z,task_error,min_distance,collided,orientation_error,min_distance_link,"
       "joint_limit_margin,manipulability,condition_number";
  for (const std::string& name : diagnostic_names) h += "," + name;
  if (with_step_us) h += ",step_us";
  h += '\n';
  return h;
}

void append_frame_csv(const Frame& f, bool with_step_us, std::string& out) {
  out += std::to_string(f.step);
  number(f.t, out);
  for (Eigen::Index i = 0; i < f.q.size(); ++i) number(f.q[i], out);
  for (Eigen::Index i = 0; i < f.qdot.size(); ++i) number(f.qdot[i], out);
  for (int i = 0; i < 3; ++i) number(f.ee_position[i], out);
  number(f.task_error, out);
  number(f.min_distance, out);
  out += f.collided ? ",1" : ",0";
  number(f.orientation_error, out);
  out += ',' + std::to_string(f.min_distance_link + 1);
  number(f.joint_limit_margin, out);
  number(f.manipulability, out);
  number(f.condition_number, out);
  for (Eigen::Index i = 0; i < f.diagnostics.size(); ++i) number(f.diagnostics[i], out);
  if (with_step_us) number(f.step_us, out);
  out += '\n';
}

}  // namespace rrlab
