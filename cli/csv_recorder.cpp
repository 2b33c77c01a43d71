#include "csv_recorder.hpp"

#include <stdexcept>

#include <rrlab/sim/frame_csv.hpp>
#include <rrlab/sim/simulator.hpp>

namespace rrlab {

CsvRecorder::CsvRecorder(const std::string& file) : out_(std::fopen(file.c_str(), "w")), file_(file) {
  if (!out_) throw std::runtime_error("cannot write '" + file + "'");
}

CsvRecorder::~CsvRecorder() {
  if (out_) std::fclose(out_);
}

void CsvRecorder::write(const std::string& text) {
  if (std::fwrite(text.data(), 1, text.size(), out_) != text.size())
    throw std::runtime_error("cannot write '" + file_ + "'");
}

void CsvRecorder::begin(const Simulator& sim) {
  write(frame_csv_header(sim.model().dof(), sim.diagnostic_names(), FrameOrigin::live));
}

void CsvRecorder::frame(const Frame& f) {
  row_.clear();
  append_frame_csv(f, FrameOrigin::live, row_);
  write(row_);
}

void CsvRecorder::end(const Summary&) {
  if (std::fflush(out_) != 0) throw std::runtime_error("cannot write '" + file_ + "'");
}

}  // namespace rrlab
