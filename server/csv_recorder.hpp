// Frames as CSV, DESIGN.md columns first:
// step,t,q1..qn,qdot1..qdotn,ee_x,ee_y,ee_z,task_error,min_distance,collided,
// then orientation_error, min_distance_link, joint_limit_margin,
// manipulability, condition_number, the method's diagnostics, and step_us last.
#pragma once

#include <cstdio>
#include <string>

#include "sim/recorder.hpp"

namespace rrlab {

class CsvRecorder final : public Recorder {
 public:
  explicit CsvRecorder(const std::string& file);  // throws std::runtime_error
  ~CsvRecorder() override;
  void begin(const Simulator& sim) override;
  void frame(const Frame& frame) override;
  void end(const Summary& summary) override;

 private:
  void number(double v);
  std::FILE* out_;
  std::string file_;
};

}  // namespace rrlab
