// A run's frames as columns, every column of `rrlab run --out`'s CSV in its
// order (sim/frame_csv.hpp): a field of several numbers is one block of
// columns (q: n, ee: 3, ee_quat: 4), the diagnostics one column each. The
// numbers are the CSV's before printing (link 1-based, 0 for none; flags 1/0),
// so that the Python package's arrays equal the CSV bit for bit. No Python
// here: module.cpp turns the columns into numpy arrays.
#pragma once

#include <string>
#include <vector>

#include <rrlab/sim/recorder.hpp>

namespace rrlab::python {

struct FrameColumn {
  std::string name;       // the field's name (q, ee, t, ...) or the diagnostic's
  int width = 1;          // numbers per frame: 1, n, 3 or 4
  bool diagnostic = false;
  enum Type { real, integer, flag } type = real;  // step and min_distance_link are whole numbers, collided a flag
  std::vector<double> values;  // frames x width, row-major
};

class FrameColumns final : public Recorder {
 public:
  void begin(const Simulator& sim) override;
  void frame(const Frame& frame) override;
  long frames() const { return frames_; }
  const std::vector<FrameColumn>& columns() const { return columns_; }

 private:
  std::vector<FrameColumn> columns_;
  long frames_ = 0;
};

}  // namespace rrlab::python
