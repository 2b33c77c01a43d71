#include <rrlab/server/app/html_export.hpp>

#include <algorithm>
#include <cstring>
#include <optional>
#include <string_view>

#include <rrlab/collision/mesh_loader.hpp>
#include <rrlab/kinematics/kinematics.hpp>
#include <rrlab/server/api/errors.hpp>
#include <rrlab/server/app/recorded_scene.hpp>
#include <rrlab/server/app/run_record_json.hpp>
#include <rrlab/sim/run_inputs.hpp>
#include <rrlab/sim/simulator.hpp>
#include <rrlab/storage/frame_codec.hpp>
#include <rrlab/storage/resimulation.hpp>
#include <rrlab/util/nesting_depth.hpp>

namespace rrlab::server {

using nlohmann::json;

namespace {

// Stored frames read per query: one batch is what a lane holds at a time.
constexpr std::int64_t kExportBatchRows = 512;
// Points of the task's path drawn behind the arm.
constexpr int kExportPathSamples = 200;
// A row's leading scalars: t, task_error, min_distance, collided, joint_limit_margin.
constexpr int kExportScalars = 5;
// Bytes the estimate adds for each lane's script lines and each batch's quotes.
constexpr std::int64_t kExportLaneSlack = 512, kExportBatchSlack = 48;

// JSON inside a <script>: every '<' escaped, so that no "</script>" or
// "<!--" in a scenario's name or a parameter ends the element early.
std::string script_json(const json& value) {
  const std::string text = value.dump(-1, ' ', false, json::error_handler_t::replace);
  std::string out;
  out.reserve(text.size() + 16);
  for (const char c : text) {
    if (c == '<')
      out += "\\u003c";
    else
      out += c;
  }
  return out;
}

constexpr char kBase64Alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

void append_base64(const std::string& bytes, std::string& out) {
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  const std::size_t n = bytes.size();
  std::size_t i = 0;
  for (; i + 3 <= n; i += 3) {
    const unsigned v = (unsigned(data[i]) << 16) | (unsigned(data[i + 1]) << 8) | unsigned(data[i + 2]);
    out += kBase64Alphabet[(v >> 18) & 63];
    out += kBase64Alphabet[(v >> 12) & 63];
    out += kBase64Alphabet[(v >> 6) & 63];
    out += kBase64Alphabet[v & 63];
  }
  if (i < n) {
    const unsigned v = (unsigned(data[i]) << 16) | (i + 1 < n ? unsigned(data[i + 1]) << 8 : 0u);
    out += kBase64Alphabet[(v >> 18) & 63];
    out += kBase64Alphabet[(v >> 12) & 63];
    out += i + 1 < n ? kBase64Alphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
}

std::int64_t base64_size(std::int64_t bytes) { return (bytes + 2) / 3 * 4; }

// A number as little-endian float32 (the viewer reads Float32Array views).
void append_float32(double value, std::string& out) {
  const float f = float(value);
  std::uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  for (int i = 0; i < 4; ++i) out += char((bits >> (8 * i)) & 0xff);
}

json point_json(const Eigen::Vector3d& p, int dims) {
  json out = json::array();
  for (int i = 0; i < dims; ++i) out.push_back(p[i]);
  return out;
}

// The obstacles as they are now, in scenario syntax; a mesh by its bounds
// in its own frame ("bounds": [min, max]), not its triangles.
json obstacles_json(const Scene& scene) {
  json list = json::array();
  for (const Obstacle& o : scene.obstacles) {
    json j = obstacle_to_json(o);
    if (o.mesh && !o.mesh->vertices.empty()) {
      Eigen::Vector3d lo = o.mesh->vertices.front(), hi = lo;
      for (const Eigen::Vector3d& v : o.mesh->vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
      }
      j["bounds"] = {{lo.x(), lo.y(), lo.z()}, {hi.x(), hi.y(), hi.z()}};
    }
    list.push_back(std::move(j));
  }
  return list;
}

// One run being written: its scene as recorded (model, obstacles, inputs),
// the kinematics workspace, and where it is.
struct ExportLane {
  storage::RunRecord run;
  std::unique_ptr<RecordedScene> scene;
  std::unique_ptr<KinematicsData> kinematics;
  int dims = 2, links = 0, row_floats = 0;
  std::int64_t last = 0;  // the last stored seq
  std::string meta;       // the lane's metadata (JSON), without frames
  std::int64_t obstacles_bytes = 0;

  // Rows written at `stride`: every stride-th seq from 0, and the last.
  std::int64_t rows(std::int64_t stride) const { return last / stride + 1 + (last % stride != 0 ? 1 : 0); }
  std::int64_t row_bytes() const { return std::int64_t(row_floats) * 4; }
  // An upper bound of what the lane adds to the file at `stride`.
  std::int64_t estimate(std::int64_t stride) const {
    const std::int64_t rows_written = rows(stride);
    const std::int64_t batches = (rows_written + kExportBatchRows - 1) / kExportBatchRows;
    const std::int64_t keyframes = std::min<std::int64_t>(std::int64_t(scene->inputs()), rows_written) + 1;
    return std::int64_t(meta.size()) + kExportLaneSlack + base64_size(rows_written * row_bytes()) +
           batches * kExportBatchSlack + keyframes * (obstacles_bytes * 2 + 128);
  }
};

ExportLane open_lane(storage::RunStore& store, const storage::RunRecord& run) {
  if (run.frames < 1)
    throw DomainError(Problem::conflict, "wrong_state", "run " + std::to_string(run.id) + " has no stored frames",
                      "id");
  ExportLane lane;
  lane.run = run;
  try {
    lane.scene = std::make_unique<RecordedScene>(run, store.events(run.id));
  } catch (const std::exception& e) {
    throw DomainError(Problem::conflict, "wrong_state",
                      "run " + std::to_string(run.id) + ": the stored scenario no longer loads: " + e.what(), "id");
  }
  const Simulator& sim = lane.scene->sim();
  const Model& model = sim.model();
  lane.kinematics = std::make_unique<KinematicsData>(model);
  lane.dims = model.kind == ModelKind::planar ? 2 : 3;
  lane.links = model.link_count();
  lane.row_floats = kExportScalars + lane.dims + 2 * lane.dims * lane.links;
  lane.last = run.frames - 1;
  lane.obstacles_bytes = std::int64_t(script_json(obstacles_json(lane.scene->sim().scene())).size());

  json radii = json::array();
  for (const Link& l : model.links) radii.push_back(l.radius);
  json path = json::array();
  if (!sim.task().is_joystick())
    for (int i = 0; i <= kExportPathSamples; ++i)
      path.push_back(point_json(sim.task().target_position(sim.scenario().duration * i / kExportPathSamples),
                                lane.dims));
  // the run as GET /api/runs/{id} shows it, and what the viewer draws from
  json meta = run_record_json(run);
  meta.update({
      {"run", run.id},
      {"stored_frames", run.frames},
      {"dt", sim.scenario().dt},
      {"duration", sim.scenario().duration},
      {"model",
       {{"kind", to_string(model.kind)},
        {"dims", lane.dims},
        {"links", lane.links},
        {"base", point_json(model.base.translation(), 3)},
        {"reach", model.reach()},
        {"radii", radii}}},
      {"task", {{"space", to_string(sim.scenario().task.space)}, {"path", path}}},
      {"row_floats", lane.row_floats},
      {"row", {"t", "task_error", "min_distance", "collided", "joint_limit_margin", "target", "links"}},
  });
  lane.meta = script_json(meta);
  return lane;
}

class HtmlExport : public BodyStream {
 public:
  HtmlExport(storage::RunStore& store, std::vector<ExportLane> lanes, std::string header, std::int64_t stride)
      : store_(store), lanes_(std::move(lanes)), header_(std::move(header)), stride_(stride) {}

  bool next(std::string& out, std::size_t target) override {
    out.clear();
    while (out.size() < target) {
      switch (stage_) {
        case Stage::head:
          out += html_viewer_head();
          out += header_;
          stage_ = lanes_.empty() ? Stage::tail : Stage::lane_start;
          break;
        case Stage::lane_start: start_lane(out); break;
        case Stage::frames: append_batch(out); break;
        case Stage::tail:
          out += html_viewer_tail();
          stage_ = Stage::done;
          break;
        case Stage::done: return false;
      }
    }
    return stage_ != Stage::done;
  }

 private:
  enum class Stage { head, lane_start, frames, tail, done };

  void start_lane(std::string& out) {
    ExportLane& lane = lanes_[lane_index_];
    out += "<script>\nRRLAB_EXPORT.lanes.push(";
    out += lane.meta;
    out += ");\nRRLAB_LANE=RRLAB_EXPORT.lanes[" + std::to_string(lane_index_) + "];RRLAB_LANE.chunks=[];RRLAB_LANE.scenes=[];\n";
    next_seq_ = 0;
    rows_ = 0;
    last_written_ = false;
    stage_ = Stage::frames;
  }

  // One batch of the lane's rows (a short query: no read lock is held while
  // the chunk is written), with the obstacle keyframes of its frames.
  void append_batch(std::string& out) {
    ExportLane& lane = lanes_[lane_index_];
    batch_.clear();
    if (next_seq_ <= lane.last) {
      store_.frames(lane.run.id, next_seq_, lane.last, stride_, [&](const storage::StoredFrame& f) {
        batch_.push_back(f);
        return std::int64_t(batch_.size()) < kExportBatchRows;
      });
      next_seq_ = std::int64_t(batch_.size()) < kExportBatchRows ? lane.last + 1 : batch_.back().seq + stride_;
    }
    if (next_seq_ > lane.last && !last_written_ && std::int64_t(batch_.size()) < kExportBatchRows) {
      // the last stored frame, when the stride passed it by
      if (batch_.empty() || batch_.back().seq != lane.last) {
        if (lane.last % stride_ != 0)
          store_.frames(lane.run.id, lane.last, lane.last, 1, [&](const storage::StoredFrame& f) {
            batch_.push_back(f);
            return false;
          });
      }
      last_written_ = true;
    }
    if (!batch_.empty()) {
      bytes_.clear();
      keyframes_.clear();
      for (const storage::StoredFrame& f : batch_) append_row(lane, f);
      out += "RRLAB_LANE.chunks.push(\"";
      append_base64(bytes_, out);
      out += "\");\n";
      out += keyframes_;
    }
    if (last_written_ || batch_.empty()) {
      // deleted meanwhile: its frames stopped short, so the body must not end as if complete
      if (!store_.run(lane.run.id))
        throw DomainError(Problem::not_found, "not_found", "run " + std::to_string(lane.run.id) + " was deleted",
                          "id");
      out += "</script>\n";
      ++lane_index_;
      stage_ = lane_index_ < lanes_.size() ? Stage::lane_start : Stage::tail;
    }
  }

  void append_row(ExportLane& lane, const storage::StoredFrame& stored) {
    const Frame frame = storage::unpack_frame(stored.data);
    // the scene's events up to this frame (a new keyframe when any changed it)
    const bool changed = lane.scene->seek(stored.seq) || rows_ == 0;
    if (changed) {
      lane.scene->sim().scene().advance_to(frame.t);
      keyframes_ += "RRLAB_LANE.scenes.push({\"row\":" + std::to_string(rows_) + ",\"t\":";
      keyframes_ += json(frame.t).dump();
      keyframes_ += ",\"obstacles\":" + script_json(obstacles_json(lane.scene->sim().scene())) + "});\n";
    }
    const Model& model = lane.scene->sim().model();
    if (frame.q.size() == model.dof())
      forward_kinematics(model, frame.q, *lane.kinematics);
    append_float32(frame.t, bytes_);
    append_float32(frame.task_error, bytes_);
    append_float32(frame.min_distance, bytes_);
    append_float32(frame.collided ? 1.0 : 0.0, bytes_);
    append_float32(frame.joint_limit_margin, bytes_);
    for (int i = 0; i < lane.dims; ++i) append_float32(frame.target[i], bytes_);
    for (int l = 0; l < lane.links; ++l) {
      for (int i = 0; i < lane.dims; ++i) append_float32(lane.kinematics->link_start(i, l), bytes_);
      for (int i = 0; i < lane.dims; ++i) append_float32(lane.kinematics->link_end(i, l), bytes_);
    }
    ++rows_;
  }

  storage::RunStore& store_;
  std::vector<ExportLane> lanes_;
  std::string header_;
  const std::int64_t stride_;  // every stride-th stored frame (and the last)
  Stage stage_ = Stage::head;
  std::size_t lane_index_ = 0;
  std::int64_t next_seq_ = 0, rows_ = 0;
  bool last_written_ = false;
  std::vector<storage::StoredFrame> batch_;
  std::string bytes_, keyframes_;
};

}  // namespace

extern const char kHtmlViewerText[];  // html_viewer_text.cpp, generated from html_viewer.html

namespace {
// The viewer split where the server writes the data.
constexpr std::string_view kHtmlViewerDataMark = "<!-- rrlab:data -->\n";
std::size_t html_viewer_split() {
  const std::size_t at = std::string_view(kHtmlViewerText).find(kHtmlViewerDataMark);
  return at == std::string_view::npos ? std::string_view(kHtmlViewerText).size() : at;
}
}  // namespace

const std::string& html_viewer_head() {
  static const std::string head(kHtmlViewerText, html_viewer_split());
  return head;
}

const std::string& html_viewer_tail() {
  static const std::string tail(std::string_view(kHtmlViewerText).substr(
      std::min(std::string_view(kHtmlViewerText).size(), html_viewer_split() + kHtmlViewerDataMark.size())));
  return tail;
}

std::shared_ptr<BodyStream> make_html_export(storage::RunStore& store, const std::vector<storage::RunRecord>& runs,
                                             const std::string& title, std::int64_t max_bytes) {
  max_bytes = std::min(max_bytes, kHtmlExportCap);
  std::vector<ExportLane> lanes;
  for (const storage::RunRecord& run : runs) lanes.push_back(open_lane(store, run));

  // the page and its header (the header's numbers are at most this wide)
  const std::int64_t header_bound = 1024 + std::int64_t(script_json(title).size());
  const std::int64_t fixed = std::int64_t(html_viewer_head().size() + html_viewer_tail().size()) + header_bound;
  const auto estimate = [&](std::int64_t stride) {
    std::int64_t total = fixed;
    for (const ExportLane& lane : lanes) total += lane.estimate(stride);
    return total;
  };
  std::int64_t longest = 1;
  for (const ExportLane& lane : lanes) longest = std::max(longest, lane.last + 1);
  // the smallest stride that fits (the estimate falls as the stride grows)
  std::int64_t lo = 1, hi = longest;
  while (lo < hi) {
    const std::int64_t mid = lo + (hi - lo) / 2;
    if (estimate(mid) <= max_bytes)
      hi = mid;
    else
      lo = mid + 1;
  }
  const std::int64_t stride = lo;
  // the fewest rows a lane would keep
  std::int64_t fewest = INT64_MAX;
  for (const ExportLane& lane : lanes) fewest = std::min(fewest, lane.rows(stride));
  std::int64_t stored_fewest = INT64_MAX;
  for (const ExportLane& lane : lanes) stored_fewest = std::min(stored_fewest, lane.last + 1);
  if (estimate(stride) > max_bytes || fewest < std::min(kHtmlExportMinFrames, stored_fewest)) {
    const std::int64_t needed = estimate(std::max<std::int64_t>(1, longest / kHtmlExportMinFrames));
    throw DomainError(Problem::too_large, "export_too_large",
                      "the file would take about " + std::to_string(needed) + " bytes with " +
                          std::to_string(kHtmlExportMinFrames) + " frames per run, over the cap of " +
                          std::to_string(max_bytes) + " bytes (max_bytes; at most " + std::to_string(kHtmlExportCap) +
                          ")",
                      "max_bytes", {{"limit", "max_bytes"}, {"requested", needed}, {"allowed", max_bytes}});
  }

  json note = nullptr;
  if (stride > 1)
    note = "Decimated to fit the cap of " + std::to_string(max_bytes) + " bytes: one stored frame in every " +
           std::to_string(stride) + " is kept (and the last); the stored run has them all (GET /api/runs/{id}/frames).";
  const std::string header = "<script>\nvar RRLAB_LANE;var RRLAB_EXPORT=" +
                             script_json({{"format", "rrlab-export"},
                                          {"version", 1},
                                          {"title", title},
                                          {"max_bytes", max_bytes},
                                          {"stride", stride},
                                          {"note", note},
                                          {"lanes", json::array()}}) +
                             ";\n</script>\n";
  return std::make_shared<HtmlExport>(store, std::move(lanes), header, stride);
}

}  // namespace rrlab::server
