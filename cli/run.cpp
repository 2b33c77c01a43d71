#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include <rrlab/scenario/scenario.hpp>
#include <rrlab/sim/run_record.hpp>
#include <rrlab/sim/simulator.hpp>
#include <rrlab/storage/frame_codec.hpp>
#include <rrlab/storage/frame_writer.hpp>
#include <rrlab/storage/resimulation.hpp>
#include <rrlab/storage/run_store.hpp>

#include "cli.hpp"
#include "csv_recorder.hpp"

namespace rrlab::cli {

namespace {

int bad_input(const std::string& message) {
  std::cerr << "rrlab: error: " << message << '\n';
  return 2;
}

// "--param NAME=VALUE": VALUE is a number or an enumeration label.
std::pair<std::string, double> parse_param(const std::string& method, const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw ScenarioError("--param " + text, "must be NAME=VALUE");
  const std::string name = text.substr(0, eq), value = text.substr(eq + 1);
  nlohmann::json v = value;
  try {
    size_t used = 0;
    const double number = std::stod(value, &used);
    if (used == value.size()) v = number;
  } catch (const std::exception&) {
  }
  return resolve_method_param(method, name, v, "--param " + name);
}

// A scenario file, or a run record with its events.
RunRecordDoc load_input(const std::string& file) {
  const nlohmann::json doc = read_json_file(file, "scenario file");
  if (is_run_record(doc)) return parse_run_record(doc);
  RunRecordDoc plain;
  const std::string dir = std::filesystem::path(file).parent_path().string();
  plain.scenario = parse_scenario(doc, dir.empty() ? "." : dir);  // a URDF "file" is next to it
  return plain;
}

}  // namespace

int run(const RunOptions& options) {
  try {
    RunRecordDoc input = load_input(options.scenario_file);
    Scenario& scenario = input.scenario;
    if (options.method && *options.method != scenario.method.name) {
      if (!input.events.empty())
        throw ScenarioError("--method", "a run record replays its own method; --method cannot change it");
      require_method(*options.method, "--method");
      scenario.method.name = *options.method;
      scenario.method.params.clear();  // the scenario's parameters belong to its own method
    }
    for (const std::string& text : options.params)
      scenario.method.params.push_back(parse_param(scenario.method.name, text));

    Simulator sim(scenario);
    long steps = sim.total_steps();
    if (input.frames > 0) steps = input.frames;  // a record: as many steps as the recorded run
    if (options.steps) steps = *options.steps;  // in [1, max_steps]: checked when parsed (main.cpp)
    sim.set_total_steps(input.events.empty() ? steps : ScenarioLimits::max_steps * 16);

    std::unique_ptr<CsvRecorder> csv;
    if (options.out_csv) csv = std::make_unique<CsvRecorder>(*options.out_csv);
    std::unique_ptr<storage::RunStore> store;
    std::unique_ptr<storage::FrameWriter> writer;
    std::int64_t run_id = 0;
    if (options.db) {
      store = std::make_unique<storage::RunStore>(*options.db);
      writer = std::make_unique<storage::FrameWriter>(*store);
      run_id = store->create_run(storage::new_run_of(scenario, sim, "batch"));
      for (const RecordedEvent& e : input.events)
        store->add_event(run_id, {e.seq, 0, e.kind, e.payload.dump()});
    }

    EventReplayer events(input.events);
    if (csv) csv->begin(sim);
    for (long seq = 0; seq < steps && !sim.done(); ++seq) {
      events.apply_due(sim, seq);
      timed_step(sim);
      if (csv) csv->frame(sim.frame());
      if (writer) {
        writer->push(run_id, storage::stored_frame(seq, sim.frame(), storage::pack_frame(sim.frame())));
      }
    }
    const Summary summary = sim.summary();
    if (csv) csv->end(summary);
    nlohmann::json out = summary_to_json(summary);
    if (writer) {
      writer->flush();
      if (!writer->last_error().empty()) throw std::runtime_error("storing frames: " + writer->last_error());
      nlohmann::json stored = out;
      stored["run"] = run_id;
      store->finish_run(run_id, "completed", stored.dump());
      out["run"] = run_id;
    }
    std::cout << out.dump() << '\n';
    return 0;
  } catch (const ScenarioError& e) {
    return bad_input(e.what());
  } catch (const ParamError& e) {
    return bad_input(std::string("method.params.") + e.what());
  } catch (const std::exception& e) {
    return bad_input(e.what());
  }
}

}  // namespace rrlab::cli
