// GET /api/runs/{id}/export.html and GET /api/compare/{group}/export.html:
// a stored run, or the runs one POST /api/compare started together (the
// group is its first lane's run id, every lane's `compare_group`), as one
// self-contained HTML file that replays offline (app/html_export.hpp). The
// request is checked here (404 unknown, 400 a bad max_bytes, 409 a run
// without frames, 413 too large for the cap); the file is then streamed.
#include <algorithm>

#include <rrlab/server/app/html_export.hpp>
#include <rrlab/server/routes/routes.hpp>

namespace rrlab::server {

namespace {

// At most this many lanes in an exported group (POST /api/compare starts at most 4).
constexpr int kExportGroupLanes = 16;

ApiResponse html_export_response(RouteContext& c, const std::vector<storage::RunRecord>& runs,
                                 const std::string& title, const std::string& file_name) {
  const std::int64_t max_bytes = query_int(c, "max_bytes", kHtmlExportCap, 1, kHtmlExportCap);
  ApiResponse response;
  response.content_type = "text/html; charset=utf-8";
  response.stream = make_html_export(c.runs.store(), runs, title, max_bytes);
  response.headers.emplace_back("Content-Disposition", "attachment; filename=\"" + file_name + "\"");
  return response;
}

}  // namespace

ApiResponse get_run_export(RouteContext& c) {
  const storage::RunRecord run = find_run(c, c.id());
  const std::string id = std::to_string(run.id);
  return html_export_response(c, {run}, "rrlab run " + id, "rrlab-run-" + id + ".html");
}

ApiResponse get_group_export(RouteContext& c) {
  const std::int64_t group = c.id();
  storage::RunFilter filter;
  filter.compare_group = group;
  filter.limit = kExportGroupLanes;
  std::vector<storage::RunRecord> runs = c.runs.store().runs(filter);
  if (runs.empty()) {
    // a lane's run id other than the first: say which group it is in
    const auto run = c.runs.store().run(group);
    const std::string hint = run && run->compare_group ? " (run " + std::to_string(group) + " is in compare group " +
                                                             std::to_string(*run->compare_group) + ")"
                                                       : "";
    throw DomainError(Problem::not_found, "not_found", "no compare group " + std::to_string(group) + hint, "id");
  }
  std::sort(runs.begin(), runs.end(), [](const auto& a, const auto& b) { return a.id < b.id; });  // lane order
  const std::string id = std::to_string(group);
  return html_export_response(c, runs, "rrlab compare " + id, "rrlab-compare-" + id + ".html");
}

}  // namespace rrlab::server
