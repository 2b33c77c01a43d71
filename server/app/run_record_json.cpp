#include <rrlab/server/app/run_record_json.hpp>

#include <rrlab/util/nesting_depth.hpp>

namespace rrlab::server {

using nlohmann::json;

json parse_or_null(const std::optional<std::string>& text) {
  if (!text) return nullptr;
  try {
    return parse_json(*text);
  } catch (const std::exception&) {
    return nullptr;
  }
}

json run_record_json(const storage::RunRecord& r) {
  return {{"id", r.id},
          {"scenario", r.scenario_name},
          {"method", r.method},
          {"params", parse_or_null(r.params_json)},
          {"seed", r.seed},
          {"mode", r.mode},
          {"created", r.created},
          {"status", r.status},
          {"frames", r.frames},
          {"frame_bytes", r.frame_bytes},
          {"dof", r.dof},
          {"diagnostic_names", parse_or_null(r.diagnostic_names_json)},
          {"summary", parse_or_null(r.summary_json)},
          {"source_run", r.source_run ? json(*r.source_run) : json()},
          {"compare_group", r.compare_group ? json(*r.compare_group) : json()},
          {"sweep", parse_or_null(r.sweep_json)}};
}

}  // namespace rrlab::server
