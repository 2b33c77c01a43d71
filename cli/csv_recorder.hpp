// `rrlab run --out`: frames as CSV (sim/frame_csv.hpp columns, step_us last).
#pragma once

#include <cstdio>
#include <string>

#include <rrlab/sim/recorder.hpp>

namespace rrlab {

class CsvRecorder final : public Recorder {
 public:
  explicit CsvRecorder(const std::string& file);  // throws std::runtime_error
  ~CsvRecorder() override;
  void begin(const Simulator& sim) override;
  void frame(const Frame& frame) override;
  void end(const Summary& summary) override;

 private:
  void write(const std::string& text);
  std::FILE* out_;
  std::string file_;
  std::string row_;  // reused
};

}  // namespace rrlab
