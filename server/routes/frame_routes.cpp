// Stored frames of a run, as JSON (default) or CSV (Accept: text/csv or
// ?format=csv), streamed: the request is checked here (404, 400), then the
// body is produced in chunks of about 64 KiB on an export worker
// (app/export_pool.hpp), each chunk from its own short query, so that no
// SQLite statement or lock is held while a client reads slowly:
// {"run", "diagnostic_names", "frames": [frames in the stream's shape, with
// "seq" and exact values (storage/frame_codec.hpp)]}.
#include <algorithm>

#include <rrlab/server/app/drawn_frames.hpp>
#include <rrlab/server/app/frame_batches.hpp>
#include <rrlab/server/routes/routes.hpp>
#include <rrlab/sim/frame_csv.hpp>
#include <rrlab/sim/frame_fields.hpp>
#include <rrlab/storage/frame_codec.hpp>
#include <rrlab/storage/run_store.hpp>
#include <rrlab/util/nesting_depth.hpp>

namespace rrlab::server {

using nlohmann::json;

namespace {

class FrameExport : public BodyStream {
 public:
  FrameExport(storage::RunStore& store, std::int64_t run, std::int64_t from, std::int64_t to, std::int64_t stride,
              std::vector<std::string> names, bool csv, int dof)
      : batches_(store, run, from, to, stride), names_(std::move(names)), csv_(csv) {
    head_ = csv ? "seq," + frame_csv_header(dof, names_, FrameOrigin::stored)
                : R"({"run":)" + std::to_string(run) + R"(,"diagnostic_names":)" + safe_dump(json(names_)) +
                      R"(,"frames":[)";
  }

  bool next(std::string& out, std::size_t target) override {
    out.clear();
    if (!head_.empty()) out.swap(head_);
    while (out.size() < target && !batches_.done()) {
      // rows for the bytes still wanted, at the size of the frames so far
      const std::size_t per_frame = frames_ > 0 ? std::max<std::size_t>(bytes_ / frames_, 1) : 4096;
      const std::size_t rows = std::clamp<std::size_t>((target - out.size()) / per_frame + 1, 1, 1024);
      // encoded after the query: the store's read lock is not held meanwhile
      for (const storage::StoredFrame& f : batches_.next(rows)) append(f, out);
    }
    if (!batches_.done()) return true;
    batches_.check_complete();
    if (!csv_) out += "]}";
    return false;
  }

 private:
  void append(const storage::StoredFrame& f, std::string& out) {
    const std::size_t before = out.size();
    if (csv_) {
      out += std::to_string(f.seq) + ',';
      append_frame_csv(storage::unpack_frame(f.data), FrameOrigin::stored, out);
    } else {
      if (frames_ > 0) out += ',';
      storage::append_stored_frame_json(f.seq, storage::unpack_frame(f.data), out);
    }
    bytes_ += out.size() - before;
    ++frames_;
  }

  FrameBatches batches_;
  const std::vector<std::string> names_;
  const bool csv_;
  std::string head_;
  std::size_t frames_ = 0, bytes_ = 0;  // written so far
};

}  // namespace

ApiResponse get_frames(RouteContext& c) {
  const storage::RunRecord run = find_run(c, c.id());
  constexpr std::int64_t kMaxFrames = 20'000;  // per request: page with from/to
  const std::int64_t from = query_int(c, "from", 0, 0, INT64_MAX / 2);
  const std::int64_t stride = query_int(c, "stride", 1, 1, 1'000'000);
  std::int64_t to = query_int(c, "to", std::max<std::int64_t>(run.frames - 1, 0), 0, INT64_MAX / 2);
  if (to < from) throw DomainError(Problem::invalid, "invalid", "must not be below from", "to");
  to = std::min(to, from + (kMaxFrames - 1) * stride);
  std::string format = "json";
  if (auto it = c.request.query.find("format"); it != c.request.query.end()) {
    if (it->second != "json" && it->second != "csv")
      throw DomainError(Problem::invalid, "invalid", "must be json or csv", "format");
    format = it->second;
  } else if (c.request.accept.find("text/csv") != std::string::npos) {
    format = "csv";
  }
  std::vector<std::string> names = parse_json(run.diagnostic_names_json).get<std::vector<std::string>>();
  ApiResponse response;
  response.content_type = format == "csv" ? "text/csv" : "application/json";
  response.stream = std::make_shared<FrameExport>(c.runs.store(), run.id, from, to, stride, std::move(names),
                                                  format == "csv", run.dof);
  return response;
}

// The frames as a replay draws them (app/drawn_frames.hpp), for the page's
// local scrubbing.
ApiResponse get_drawn_frames(RouteContext& c) {
  const storage::RunRecord run = find_run(c, c.id());
  const std::int64_t from = query_int(c, "from", 0, 0, INT64_MAX / 2);
  const std::int64_t stride = query_int(c, "stride", 1, 1, 1'000'000);
  const std::int64_t to = query_int(c, "to", std::max<std::int64_t>(run.frames - 1, 0), 0, INT64_MAX / 2);
  if (run.frames > 0 && from > run.frames - 1)
    throw DomainError(Problem::invalid, "invalid", "must be in [0, " + std::to_string(run.frames - 1) + "]", "from");
  if (to < from) throw DomainError(Problem::invalid, "invalid", "must not be below from", "to");
  ApiResponse response;
  response.content_type = "application/x-ndjson";
  response.stream = make_drawn_frames(c.runs.store(), run, from, to, stride);
  return response;
}

ApiResponse get_frame_fields(RouteContext&) {
  static const json fields = [] {
    json list = json::array();
    for (const FrameField& field : kFrameFields) {
      json outputs = json::array();
      if (field.outputs & kFrameBlob) outputs.push_back("stored");
      if (field.outputs & kFrameCsv) outputs.push_back("csv");
      if (field.outputs & kFrameJson) outputs.push_back("json");
      list.push_back({{"name", field.name},
                      {"unit", field.unit},
                      {"kind", frame_field_kind_name(field.kind)},
                      {"metric", field.metric},
                      {"outputs", outputs},
                      {"description", field.description}});
    }
    return json{{"blob_version", kFrameBlobVersion}, {"fields", list}};
  }();
  return json_response(200, fields);
}

}  // namespace rrlab::server
