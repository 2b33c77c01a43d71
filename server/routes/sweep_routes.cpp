// Sweeps over REST: POST /api/sweeps starts one (202), GET /api/sweeps/{id}
// gives its progress and, once ended, its report; POST .../control stops it.
#include <iterator>
#include <optional>

#include <rrlab/server/app/sweep_jobs.hpp>
#include <rrlab/server/routes/routes.hpp>
#include <rrlab/sweep/sweep_spec.hpp>

namespace rrlab::server {

using nlohmann::json;

namespace {

// Over REST a scenario entry is a catalogue name or a generator: never a path.
void refuse_paths(const json& spec) {
  if (!spec.is_object() || !spec.contains("scenarios") || !spec["scenarios"].is_array()) return;
  const json& list = spec["scenarios"];
  for (size_t i = 0; i < list.size(); ++i) {
    // a scenario entry, or the scenario a perturbation family perturbs
    const bool perturbs = list[i].is_object() && list[i].contains("perturb") && list[i]["perturb"].is_string();
    if (!list[i].is_string() && !perturbs) continue;
    const std::string name = perturbs ? list[i]["perturb"].get<std::string>() : list[i].get<std::string>();
    if (!sweep::is_plain_name(name) || name.ends_with(".json"))
      throw DomainError(Problem::unprocessable, "invalid",
                        "over REST a sweep names catalogue scenarios or generators, not files: '" + name + "'",
                        "scenarios[" + std::to_string(i) + "]" + (perturbs ? ".perturb" : ""));
  }
}

// A sweep spec of a request body: catalogue scenarios and generators only
// (unprocessable naming the path otherwise).
sweep::SweepSpec parse_sweep_request(RouteContext& c) {
  const json body = parse_body(c.request);
  refuse_paths(body);
  const std::string& dir = c.runs.catalogue().dir();
  try {
    return sweep::parse_sweep_spec(body, {dir, dir});
  } catch (...) {
    rethrow_as_domain_error("", Problem::unprocessable);
  }
}

}  // namespace

ApiResponse post_sweep(RouteContext& c) {
  const int jobs = int(query_int(c, "jobs", 1, 1, 256));
  c.runs.check_writable();  // a full disk first: a sweep would store nothing, whatever its spec
  return json_response(202, c.runs.sweeps().start(parse_sweep_request(c), jobs));
}

ApiResponse list_sweeps(RouteContext& c) { return json_response(200, c.runs.sweeps().list()); }

ApiResponse get_sweep(RouteContext& c) {
  ApiResponse response;
  response.body = c.runs.sweeps().status(c.id());
  return response;
}

// Checks a spec as POST /api/sweeps would and starts nothing (the dashboard's dialog).
ApiResponse validate_sweep(RouteContext& c) {
  return json_response(200, c.runs.sweeps().validate(parse_sweep_request(c)));
}

namespace {

// Every run of a sweep that matches a filter, as CSV (one row per run, the
// columns of the JSON page): streamed on an export worker, 500 rows read from
// SQL at a time by key (each row once, even while the sweep stores more), so
// that the whole of a sweep of 100,000 runs costs the server one page of
// memory however it is filtered.
class SweepRunsCsv : public BodyStream {
 public:
  SweepRunsCsv(storage::RunStore& store, std::string sweep, storage::RunStore::SweepRunFilter filter,
               std::int64_t offset)
      : store_(store), sweep_(std::move(sweep)), filter_(std::move(filter)), offset_(offset) {}

  bool next(std::string& out, std::size_t target) override {
    out.clear();
    if (!header_done_) {
      for (size_t i = 0; i < std::size(kColumns); ++i) out += (i ? "," : "") + std::string(kColumns[i]);
      out += '\n';
      header_done_ = true;
    }
    while (out.size() < target && more_) {
      // the first page from the client's offset, the next ones after the last key read
      std::int64_t total = 0;
      const std::vector<storage::SweepRunEntry> page =
          last_key_ ? store_.sweep_runs_after(sweep_, filter_, *last_key_, kPage)
                    : store_.sweep_runs_page(sweep_, filter_, kPage, offset_, total);
      for (const storage::SweepRunEntry& e : page) append_row(sweep_run_json(e), out);
      if (!page.empty()) last_key_ = page.back().row.key;
      more_ = std::int64_t(page.size()) == kPage;
    }
    return more_;
  }

 private:
  static constexpr std::int64_t kPage = 500;
  static constexpr const char* kColumns[] = {"run",     "key",       "case",   "config",   "family",
                                             "success", "failure_mode", "failure_t", "frames", "steps",
                                             "collided", "min_distance", "max_tracking_error", "difficulty"};

  static void append_row(const nlohmann::json& row, std::string& out) {
    for (size_t i = 0; i < std::size(kColumns); ++i) {
      if (i) out += ',';
      const nlohmann::json& value = row[kColumns[i]];
      if (value.is_null()) continue;
      const std::string text = value.is_string() ? value.get<std::string>() : safe_dump(value);
      if (text.find_first_of(",\"\n") == std::string::npos) {
        out += text;
        continue;
      }
      out += '"';  // a field with a comma, quote or newline (a key, the difficulty object) is quoted
      for (char ch : text) out += ch == '"' ? std::string("\"\"") : std::string(1, ch);
      out += '"';
    }
    out += '\n';
  }

  storage::RunStore& store_;
  const std::string sweep_;
  const storage::RunStore::SweepRunFilter filter_;
  const std::int64_t offset_;
  std::optional<std::string> last_key_;  // of the last row sent
  bool header_done_ = false, more_ = true;
};

}  // namespace

// ?family=&config=&outcome=pass|fail&failure_mode=&limit=&offset=; as CSV
// (Accept: text/csv or ?format=csv) every matching run from offset, streamed.
ApiResponse get_sweep_runs(RouteContext& c) {
  SweepJobs::RunQuery query;
  const auto& q = c.request.query;
  const auto text = [&](const char* name) -> std::optional<std::string> {
    auto it = q.find(name);
    return it == q.end() || it->second.empty() ? std::nullopt : std::optional<std::string>(it->second);
  };
  query.family = text("family");
  query.config = text("config");
  query.failure_mode = text("failure_mode");
  if (const auto outcome = text("outcome")) {
    if (*outcome != "pass" && *outcome != "fail")
      throw DomainError(Problem::invalid, "invalid", "must be pass or fail", "outcome");
    query.success = *outcome == "pass";
  }
  query.limit = query_int(c, "limit", 100, 1, 1000);
  query.offset = query_int(c, "offset", 0, 0, 1'000'000'000);
  bool csv = c.request.accept.find("text/csv") != std::string::npos;
  if (const auto format = text("format")) {
    if (*format != "json" && *format != "csv")
      throw DomainError(Problem::invalid, "invalid", "must be json or csv", "format");
    csv = *format == "csv";
  }
  if (!csv) return json_response(200, c.runs.sweeps().runs(c.id(), query));
  ApiResponse response;
  response.content_type = "text/csv";
  response.stream =
      std::make_shared<SweepRunsCsv>(c.runs.store(), c.runs.sweeps().name(c.id()), query.filter(), query.offset);
  return response;
}

// {"action": "stop"}, the only control a sweep takes.
ApiResponse post_sweep_control(RouteContext& c) {
  const json body = parse_body(c.request);
  if (!body.is_object() || body.size() != 1 || !body.contains("action") || body["action"] != "stop")
    throw DomainError(Problem::invalid, "invalid", "a sweep takes {\"action\": \"stop\"}", "action");
  return json_response(200, c.runs.sweeps().stop(c.id()));
}

}  // namespace rrlab::server
