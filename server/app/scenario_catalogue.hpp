// The scenarios a run can name: the files of scenarios/ (read once, at
// start) and those added over REST (stored in the database, never on disk,
// never replaced).
#pragma once

#include <cstdint>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace rrlab::storage {
class RunStore;
}

namespace rrlab::server {

class ScenarioCatalogue {
 public:
  // Reads every valid scenario file of `dir` (none if it is empty or not a
  // directory); keeps at most `max_scenarios` added ones.
  ScenarioCatalogue(storage::RunStore& store, const std::string& dir, std::int64_t max_scenarios);

  const std::string& dir() const { return dir_; }
  // {"scenarios": [summary...], "total", "offset", "limit"}, files of
  // scenarios/ first (by stem), then stored ones (by name); a summary is
  // {name, title, description (at most 200 characters), source, builtin,
  // kind, dof, obstacles, bytes} (bytes: the scenario's JSON text).
  nlohmann::json list(std::int64_t limit, std::int64_t offset);
  // A scenario by catalogue name (file stem or its "name") or stored name; not_found otherwise.
  nlohmann::json document(const std::string& name);
  // Stores `document` as `name` (1 to 64 of [A-Za-z0-9_.-]): {"name"}.
  // unprocessable when a run would refuse it, conflict ("exists") when the
  // name is taken, quota beyond max_scenarios.
  nlohmann::json add(const std::string& name, const nlohmann::json& document);
  // {"valid": true, name, exists, kind, dof, ...} for a scenario a run would
  // accept (unprocessable naming the path otherwise).
  nlohmann::json validate(const nlohmann::json& document);
  // The snapshot a run of catalogue scenario `name` would start its stream
  // with, frame 0 included (stream_json.hpp preview_snapshot_json), built as
  // validate builds it and stored nowhere. invalid for a name that is not 1
  // to 64 of [A-Za-z0-9_.-], not_found for an unknown one, unprocessable
  // naming the path for a stored scenario a run would now refuse.
  nlohmann::json preview(const std::string& name);

 private:
  nlohmann::json summary(const std::string& name, const nlohmann::json& doc, bool builtin);

  storage::RunStore& store_;
  const std::string dir_;
  const std::int64_t max_scenarios_;
  std::map<std::string, nlohmann::json> files_;  // file scenarios by stem and by name
  std::vector<std::string> file_names_;          // file stems, sorted
  std::mutex summaries_mutex_;
  std::map<std::string, nlohmann::json> stored_summaries_;  // stored scenarios never change: computed once
};

}  // namespace rrlab::server
