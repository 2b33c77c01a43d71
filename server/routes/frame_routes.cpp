// Stored frames of a run, as JSON (default) or CSV (Accept: text/csv or ?format=csv).
#include "routes/routes.hpp"
#include "sim/frame_csv.hpp"
#include "storage/frame_codec.hpp"
#include "storage/run_store.hpp"

namespace rrlab::server {

using nlohmann::json;

ApiResponse get_frames(RouteContext& c) {
  const storage::RunRecord run = find_run(c, c.id());
  constexpr std::int64_t kMaxFrames = 20'000;  // per request (bounded memory): page with from/to
  const std::int64_t from = query_int(c, "from", 0, 0, INT64_MAX / 2);
  const std::int64_t stride = query_int(c, "stride", 1, 1, 1'000'000);
  std::int64_t to = query_int(c, "to", std::max<std::int64_t>(run.frames - 1, 0), 0, INT64_MAX / 2);
  if (to < from) throw ApiError(400, "invalid", "must not be below from", "to");
  to = std::min(to, from + (kMaxFrames - 1) * stride);
  std::string format = "json";
  if (auto it = c.request.query.find("format"); it != c.request.query.end()) {
    if (it->second != "json" && it->second != "csv") throw ApiError(400, "invalid", "must be json or csv", "format");
    format = it->second;
  } else if (c.request.accept.find("text/csv") != std::string::npos) {
    format = "csv";
  }
  const std::vector<std::string> names = json::parse(run.diagnostic_names_json).get<std::vector<std::string>>();
  ApiResponse response;
  if (format == "csv") {
    response.content_type = "text/csv";
    response.body = "seq," + frame_csv_header(run.dof, names, false);
    c.runs.store().frames(run.id, from, to, stride, [&](const storage::StoredFrame& f) {
      response.body += std::to_string(f.seq) + ',';
      append_frame_csv(storage::unpack_frame(f.data), false, response.body);
      return true;
    });
    return response;
  }
  json frames = json::array();
  c.runs.store().frames(run.id, from, to, stride, [&](const storage::StoredFrame& f) {
    json frame = storage::frame_to_json(storage::unpack_frame(f.data), names);
    frame["seq"] = f.seq;
    frames.push_back(std::move(frame));
    return true;
  });
  return json_response(200, {{"run", run.id}, {"diagnostic_names", names}, {"frames", frames}});
}

}  // namespace rrlab::server
