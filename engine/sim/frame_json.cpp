#include <rrlab/sim/frame_json.hpp>

#include <rrlab/util/number_text.hpp>

namespace rrlab {

void append_frame_json_members(const Frame& frame, FrameOrigin origin, int digits, std::string& out) {
  std::array<double, 4> scratch{};
  bool first = true, in_metrics = false;
  for (const FrameField& field : kFrameFields) {
    if (!frame_writes(field, kFrameJson, origin, frame)) continue;
    if (field.metric && !in_metrics) {  // the metrics are consecutive in the table
      out += first ? "\"metrics\":{" : ",\"metrics\":{";
      first = in_metrics = true;
    } else if (!field.metric && in_metrics) {
      out += '}';
      in_metrics = false;
    }
    if (!first) out += ',';
    first = false;
    out += '"';
    out += field.name;
    out += "\":";
    const std::span<const double> values = frame_values(frame, field.id, scratch);
    switch (field.kind) {
      case FrameFieldKind::count: append_integer((long long)(values[0]), out); break;
      case FrameFieldKind::link: append_integer((long long)(values[0]) + 1, out); break;
      case FrameFieldKind::flag: out += values[0] != 0.0 ? "true" : "false"; break;
      case FrameFieldKind::number: append_json_number(values[0], digits, out); break;
      case FrameFieldKind::joints:
      case FrameFieldKind::vec3:
      case FrameFieldKind::quaternion:
      case FrameFieldKind::diagnostics:
        out += '[';
        for (size_t i = 0; i < values.size(); ++i) {
          if (i) out += ',';
          append_json_number(values[i], digits, out);
        }
        out += ']';
        break;
    }
  }
  if (in_metrics) out += '}';
}

}  // namespace rrlab
