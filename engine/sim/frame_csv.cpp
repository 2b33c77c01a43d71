#include <rrlab/sim/frame_csv.hpp>

#include <rrlab/util/number_text.hpp>

namespace rrlab {

namespace {

// A frame that only sizes the columns: the header needs no values.
Frame shape_of(int dof, size_t diagnostics) {
  Frame f;
  f.q.resize(dof);
  f.qdot.resize(dof);
  f.diagnostics.resize(Eigen::Index(diagnostics));
  return f;
}

}  // namespace

std::string frame_csv_header(int dof, const std::vector<std::string>& diagnostic_names, FrameOrigin origin) {
  static constexpr const char* kAxes[] = {"_x", "_y", "_z"};
  static constexpr const char* kQuaternion[] = {"_w", "_x", "_y", "_z"};
  const Frame shape = shape_of(dof, diagnostic_names.size());
  std::string h;
  for (const FrameField& field : kFrameFields) {
    if (!frame_writes(field, kFrameCsv, origin, shape)) continue;
    const int n = frame_value_count(field.kind, dof, int(diagnostic_names.size()));
    for (int i = 0; i < n; ++i) {
      if (!h.empty()) h += ',';
      switch (field.kind) {
        case FrameFieldKind::diagnostics: h += diagnostic_names[size_t(i)]; break;
        case FrameFieldKind::joints: h.append(field.name).append(std::to_string(i + 1)); break;
        case FrameFieldKind::vec3: h.append(field.name).append(kAxes[i]); break;
        case FrameFieldKind::quaternion: h.append(field.name).append(kQuaternion[i]); break;
        default: h += field.name;
      }
    }
  }
  h += '\n';
  return h;
}

void append_frame_csv(const Frame& frame, FrameOrigin origin, std::string& out) {
  std::array<double, 4> scratch{};
  bool first = true;
  for (const FrameField& field : kFrameFields) {
    if (!frame_writes(field, kFrameCsv, origin, frame)) continue;
    for (const double v : frame_values(frame, field.id, scratch)) {
      if (!first) out += ',';
      first = false;
      switch (field.kind) {
        case FrameFieldKind::count: append_integer((long long)(v), out); break;
        case FrameFieldKind::link: append_integer((long long)(v) + 1, out); break;
        case FrameFieldKind::flag: out += v != 0.0 ? '1' : '0'; break;
        default:
          if (std::isfinite(v)) append_number(v, 0, out);
      }
    }
  }
  out += '\n';
}

}  // namespace rrlab
