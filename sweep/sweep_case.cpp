#include <rrlab/sweep/sweep_case.hpp>

#include <deque>
#include <mutex>

#include <rrlab/generators/generators.hpp>
#include <rrlab/generators/perturbation.hpp>
#include <rrlab/methods/registry.hpp>
#include <rrlab/sim/recorder.hpp>
#include <rrlab/sim/simulator.hpp>
#include <rrlab/storage/frame_codec.hpp>
#include <rrlab/storage/quotas.hpp>
#include <rrlab/storage/resimulation.hpp>
#include <rrlab/sweep/failure_watch.hpp>

namespace rrlab::sweep {

namespace {

constexpr size_t kMaxStoredFrames = Quotas{}.max_run_frames;  // per run, as the server stores at most

// Frames as stored, numbered from 0 like `rrlab run --db`.
class FrameCollector : public Recorder {
 public:
  explicit FrameCollector(std::vector<storage::StoredFrame>& out) : out_(out) {}
  void frame(const Frame& frame) override {
    if (out_.size() >= kMaxStoredFrames) return;
    const auto seq = std::int64_t(out_.size());
    out_.push_back(storage::stored_frame(seq, frame, storage::pack_frame(frame)));
  }

 private:
  std::vector<storage::StoredFrame>& out_;
};

}  // namespace

std::shared_ptr<const Scenario> generated_case(const ScenarioEntry& entry, int index) {
  // the runs of one case (its method configurations and seeds) follow each
  // other in the expansion: the last few cases made serve them all
  constexpr size_t kKept = 16;
  static std::mutex mutex;
  static std::deque<std::pair<std::string, std::shared_ptr<const Scenario>>> kept;
  const std::string key = entry.family + '\n' + entry.dir + '\n' + entry.options.dump() + '\n' + std::to_string(entry.seed) + '\n' +
                          std::to_string(index);
  {
    std::lock_guard lock(mutex);
    for (const auto& [k, scenario] : kept)
      if (k == key) return scenario;
  }
  auto made = std::make_shared<const Scenario>(
      entry.perturbs()
          ? parse_scenario(perturb_scenario(entry.scenario->json, entry.dir, entry.name, entry.perturbation, entry.perturbation_scale,
                                            entry.seed, index),
                           entry.dir)
          : parse_scenario(generate_scenario(entry.family, entry.options, entry.seed, index)));
  std::lock_guard lock(mutex);
  kept.emplace_back(key, made);
  if (kept.size() > kKept) kept.pop_front();
  return made;
}

void use_method_config(Scenario& scenario, const MethodConfig& config) {
  scenario.method.name = config.method;
  scenario.method.params.clear();
  for (const ParamValue& p : config.params) scenario.method.params.emplace_back(p.name, p.value);
}

Scenario scenario_of_case(const SweepSpec& spec, const SweepCase& c) {
  const ScenarioEntry& entry = spec.scenarios.at(c.entry);
  Scenario scenario = entry.generated() ? *generated_case(entry, c.index) : *entry.scenario;
  if (!entry.generated() && !entry.name.empty()) {
    // one name everywhere: a file's runs carry its catalogue name (the file's stem), as the server's do
    scenario.name = entry.name;
    scenario.json["name"] = entry.name;
  }
  const MethodConfig& config = spec.configs.at(c.config);
  use_method_config(scenario, config);
  nlohmann::json params = nlohmann::json::object();
  for (const ParamValue& p : config.params) params[p.name] = p.value;
  scenario.json["method"] = {{"name", config.method}, {"params", params}};
  if (const MethodInfo* info = find_method(config.method); info && info->python)
    scenario.json["method"]["origin"] = "python";  // its stored runs say where the method lives
  if (c.seed) {
    scenario.seed = *c.seed;
    scenario.json["seed"] = *c.seed;
  }
  return scenario;
}

CaseResult run_case(const SweepSpec& spec, const SweepCase& c, bool with_frames, const std::atomic<bool>* stop) {
  const Scenario scenario = scenario_of_case(spec, c);
  Simulator sim(scenario);
  if (spec.steps) sim.set_total_steps(*spec.steps);

  CaseResult result;
  FrameCollector collector(result.run.frames);
  if (with_frames) result.run.frames.reserve(size_t(std::min<long>(sim.total_steps(), kMaxStoredFrames)));
  FailureWatch watch(spec.success, with_frames ? &collector : nullptr);
  result.summary = run_to_end(sim, &watch, stop);

  result.run.run = storage::new_run_of(scenario, sim, "batch");
  result.run.summary_json = summary_to_json(result.summary).dump();

  const bool success = judge_success(spec.success, result.summary) && watch.tracking_held();
  result.row = {spec.name, c.key, c.scenario_key, c.config_key, c.family, success, std::nullopt, std::nullopt};
  if (const std::optional<FirstFailure> failure = watch.first(success)) {
    result.row.failure_mode = failure->mode;
    result.row.failure_t = failure->t;
  }
  return result;
}

}  // namespace rrlab::sweep
