#include "frame_columns.hpp"

#include <array>

#include <rrlab/sim/frame_fields.hpp>
#include <rrlab/sim/simulator.hpp>

namespace rrlab::python {

void FrameColumns::begin(const Simulator& sim) {
  columns_.clear();
  frames_ = 0;
  const int dof = sim.model().dof();
  const std::vector<std::string>& diagnostics = sim.diagnostic_names();
  for (const FrameField& field : kFrameFields) {
    if ((field.outputs & kFrameCsv) == 0) continue;  // the CSV's columns only
    if (field.kind == FrameFieldKind::diagnostics) {
      for (const std::string& name : diagnostics) columns_.push_back({name, 1, true, FrameColumn::real, {}});
      continue;
    }
    const FrameColumn::Type type = field.kind == FrameFieldKind::flag ? FrameColumn::flag
                                   : field.kind == FrameFieldKind::count || field.kind == FrameFieldKind::link
                                       ? FrameColumn::integer
                                       : FrameColumn::real;
    columns_.push_back({std::string(field.name), frame_value_count(field.kind, dof, 0), false, type, {}});
  }
}

void FrameColumns::frame(const Frame& frame) {
  std::array<double, 4> scratch{};
  size_t column = 0;
  for (const FrameField& field : kFrameFields) {
    if ((field.outputs & kFrameCsv) == 0) continue;
    const std::span<const double> values = frame_values(frame, field.id, scratch);
    if (field.kind == FrameFieldKind::diagnostics) {
      for (const double v : values) columns_[column++].values.push_back(v);
      continue;
    }
    FrameColumn& out = columns_[column++];
    for (const double v : values) {
      switch (field.kind) {
        case FrameFieldKind::link: out.values.push_back(v + 1); break;  // 1-based, 0 for none
        case FrameFieldKind::flag: out.values.push_back(v != 0.0 ? 1.0 : 0.0); break;
        default: out.values.push_back(v);
      }
    }
  }
  ++frames_;
}

}  // namespace rrlab::python
