#include "csv_recorder.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>

#include "sim/simulator.hpp"

namespace rrlab {

CsvRecorder::CsvRecorder(const std::string& file) : out_(std::fopen(file.c_str(), "w")), file_(file) {
  if (!out_) throw std::runtime_error("cannot write '" + file + "'");
}

CsvRecorder::~CsvRecorder() {
  if (out_) std::fclose(out_);
}

void CsvRecorder::begin(const Simulator& sim) {
  const int n = sim.model().dof();
  std::fputs("step,t", out_);
  for (int i = 1; i <= n; ++i) std::fprintf(out_, ",q%d", i);
  for (int i = 1; i <= n; ++i) std::fprintf(out_, ",qdot%d", i);
  std::fputs(",ee_x,ee_y,ee_z,task_error,min_distance,collided,orientation_error,min_distance_link,"
             "joint_limit_margin,manipulability,condition_number",
             out_);
  for (const std::string& name : sim.diagnostic_names()) std::fprintf(out_, ",%s", name.c_str());
  std::fputs(",step_us\n", out_);
}

// Shortest text that reads back to the same double; empty for inf/NaN.
void CsvRecorder::number(double v) {
  std::fputc(',', out_);
  if (!std::isfinite(v)) return;
  char buf[32];
  const auto result = std::to_chars(buf, buf + sizeof buf, v);
  std::fwrite(buf, 1, size_t(result.ptr - buf), out_);
}

void CsvRecorder::frame(const Frame& f) {
  std::fprintf(out_, "%ld", f.step);
  number(f.t);
  for (Eigen::Index i = 0; i < f.q.size(); ++i) number(f.q[i]);
  for (Eigen::Index i = 0; i < f.qdot.size(); ++i) number(f.qdot[i]);
  for (int i = 0; i < 3; ++i) number(f.ee_position[i]);
  number(f.task_error);
  number(f.min_distance);
  std::fprintf(out_, ",%d", f.collided ? 1 : 0);
  number(f.orientation_error);
  std::fprintf(out_, ",%d", f.min_distance_link + 1);  // 1-based link, 0: none
  number(f.joint_limit_margin);
  number(f.manipulability);
  number(f.condition_number);
  for (Eigen::Index i = 0; i < f.diagnostics.size(); ++i) number(f.diagnostics[i]);
  number(f.step_us);
  std::fputc('\n', out_);
}

void CsvRecorder::end(const Summary&) {
  if (std::fflush(out_) != 0) throw std::runtime_error("cannot write '" + file_ + "'");
}

}  // namespace rrlab
