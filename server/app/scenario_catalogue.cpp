#include <rrlab/server/app/scenario_catalogue.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>
#include <regex>
#include <sstream>

#include <rrlab/methods/method.hpp>
#include <rrlab/scenario/scenario.hpp>
#include <rrlab/server/api/errors.hpp>
#include <rrlab/server/app/stream_json.hpp>
#include <rrlab/sim/simulator.hpp>
#include <rrlab/storage/run_store.hpp>
#include <rrlab/util/nesting_depth.hpp>

namespace rrlab::server {

using nlohmann::json;

namespace {

// A string field of a scenario, cut to `limit` bytes (whole UTF-8 characters,
// then an ellipsis): a list answers summaries, however long a field is.
std::string excerpt(const json& doc, const char* key, const std::string& otherwise, size_t limit) {
  std::string text = doc.contains(key) && doc[key].is_string() ? doc[key].get<std::string>() : otherwise;
  if (text.size() <= limit) return text;
  size_t cut = limit;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;
  return text.substr(0, cut) + "\u2026";
}

// A scenario as a run would take it: parsed, and its simulator built (some
// parameters are checked against the arm only there). Unprocessable naming the path.
std::unique_ptr<Simulator> checked_simulator(const json& document) {
  try {
    return std::make_unique<Simulator>(parse_scenario(document));
  } catch (const ParamError& e) {
    const std::string path = e.param() == "method" ? "method.name" : "method.params." + e.param();
    throw DomainError(Problem::unprocessable, "invalid", path + ": " + e.what(), path);
  } catch (...) {
    rethrow_as_domain_error("", Problem::unprocessable);
  }
}

Scenario checked_scenario(const json& document) { return checked_simulator(document)->scenario(); }

// A scenario's name: 1 to 64 of [A-Za-z0-9_.-] (invalid otherwise).
void check_name(const std::string& name) {
  static const std::regex pattern("[A-Za-z0-9_.-]{1,64}");
  if (!std::regex_match(name, pattern))
    throw DomainError(Problem::invalid, "invalid", "must be 1 to 64 letters, digits, '_', '-' or '.'", "name");
}

}  // namespace

ScenarioCatalogue::ScenarioCatalogue(storage::RunStore& store, const std::string& dir, std::int64_t max_scenarios)
    : store_(store), dir_(dir), max_scenarios_(max_scenarios) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (dir.empty() || !fs::is_directory(dir, ec)) return;
  set_scenario_catalogue_dir(dir);  // where a URDF robot's "file" is resolved
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    if (entry.path().extension() != ".json") continue;
    std::ifstream in(entry.path());
    std::stringstream text;
    text << in.rdbuf();
    try {
      const Scenario scenario = parse_scenario_text(text.str());  // only valid files are served
      const std::string stem = entry.path().stem().string();
      // one name everywhere: a catalogue scenario is named by its file, in
      // the list, in its document and so in the runs stored from it; its
      // inner name still finds it
      json doc = scenario.json;
      doc["name"] = stem;
      files_[stem] = doc;
      files_.emplace(scenario.name, std::move(doc));
      file_names_.push_back(stem);
    } catch (const std::exception&) {
    }
  }
  std::sort(file_names_.begin(), file_names_.end());
}

json ScenarioCatalogue::summary(const std::string& name, const json& doc, bool builtin) {
  json summary = {{"name", name},
                  {"title", excerpt(doc, "name", name, 128)},
                  {"description", excerpt(doc, "description", "", 200)},
                  {"source", excerpt(doc, "source", "", 200)},
                  {"builtin", builtin},
                  {"kind", nullptr},
                  {"dof", nullptr},
                  {"obstacles", nullptr},
                  {"bytes", doc.dump().size()}};
  try {
    const Scenario scenario = parse_scenario(doc);
    summary["kind"] = to_string(scenario.model.kind);
    summary["dof"] = scenario.model.dof();
    summary["obstacles"] = scenario.scene.obstacles.size();
  } catch (const std::exception&) {
    // stored under older rules: listed, with what the summary cannot say as null
  }
  return summary;
}

json ScenarioCatalogue::list(std::int64_t limit, std::int64_t offset) {
  const std::vector<std::string> stored = store_.scenario_names();
  const std::int64_t builtin = std::int64_t(file_names_.size());
  const std::int64_t total = builtin + std::int64_t(stored.size());
  json list = json::array();
  for (std::int64_t i = offset; i < total && i < offset + limit; ++i) {
    if (i < builtin) {
      const std::string& stem = file_names_[size_t(i)];
      list.push_back(summary(stem, files_.at(stem), true));
      continue;
    }
    const std::string& name = stored[size_t(i - builtin)];
    {
      std::lock_guard lock(summaries_mutex_);
      if (auto it = stored_summaries_.find(name); it != stored_summaries_.end()) {
        list.push_back(it->second);
        continue;
      }
    }
    const auto text = store_.scenario(name);
    if (!text) continue;  // deleted meanwhile
    json made = summary(name, parse_json(*text), false);
    std::lock_guard lock(summaries_mutex_);
    stored_summaries_[name] = made;
    list.push_back(std::move(made));
  }
  return {{"scenarios", list}, {"total", total}, {"offset", offset}, {"limit", limit}};
}

json ScenarioCatalogue::document(const std::string& name) {
  if (auto it = files_.find(name); it != files_.end()) return it->second;
  if (auto stored = store_.scenario(name)) return parse_json(*stored);
  throw DomainError(Problem::not_found, "not_found", "no scenario \"" + name + "\"", "scenario");
}

json ScenarioCatalogue::add(const std::string& name, const json& document) {
  check_name(name);
  checked_scenario(document);
  // never replaces: a file of scenarios/ nor one added earlier (runs name their scenario)
  const auto exists = [&] {
    return DomainError(Problem::conflict, "exists", "a scenario \"" + name + "\" exists already; choose another name",
                       "name");
  };
  if (files_.count(name)) throw exists();
  switch (store_.put_scenario(name, document.dump(), max_scenarios_)) {
    case storage::PutScenario::added: break;
    case storage::PutScenario::exists: throw exists();
    case storage::PutScenario::full:
      throw DomainError(Problem::quota, "storage_quota",
                        "max_scenarios: " + std::to_string(max_scenarios_) +
                            " scenarios are stored, the most this server keeps (serve --max-scenarios); "
                            "this one is not stored",
                        "",
                        {{"limit", "max_scenarios"}, {"stored", store_.scenario_count()}, {"allowed", max_scenarios_}});
  }
  return {{"name", name}};
}

json ScenarioCatalogue::validate(const json& document) {
  const Scenario scenario = checked_scenario(document);
  const bool exists = files_.count(scenario.name) > 0 || store_.scenario(scenario.name).has_value();
  return {{"valid", true},
          {"name", scenario.name},
          {"exists", exists},
          {"kind", to_string(scenario.model.kind)},
          {"dof", scenario.model.dof()},
          {"links", scenario.model.link_count()},
          {"obstacles", scenario.scene.obstacles.size()},
          {"task", {{"space", to_string(scenario.task.space)}, {"trajectory", to_string(scenario.task.trajectory.type)}}},
          {"method", scenario.method.name},
          {"dt", scenario.dt},
          {"duration", scenario.duration},
          {"steps", scenario.steps()}};
}

json ScenarioCatalogue::preview(const std::string& name) {
  check_name(name);
  return preview_snapshot_json(*checked_simulator(document(name)));
}

}  // namespace rrlab::server
