#include "sweeps.hpp"

#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <future>
#include <sstream>

#include <rrlab/generators/generators.hpp>
#include <rrlab/methods/registry.hpp>
#include <rrlab/scenario/scenario.hpp>
#include <rrlab/storage/resimulation.hpp>
#include <rrlab/storage/run_store.hpp>
#include <rrlab/sweep/summaries_csv.hpp>
#include <rrlab/sweep/sweep_report.hpp>
#include <rrlab/sweep/sweep_report_json.hpp>
#include <rrlab/sweep/sweep_runner.hpp>
#include <rrlab/sweep/sweep_spec.hpp>
#include <rrlab/util/nesting_depth.hpp>

#include "method_reentry.hpp"
#include "python_method.hpp"
#include "whole_number.hpp"

namespace py = pybind11;

namespace rrlab::python {

namespace {

// A Python method found by name from now on (sweep specs, scenarios).
std::string register_method(const py::object& method) {
  const std::string name = python_method_name(method);
  MethodInfo info;
  info.name = name;
  const py::object doc = py::getattr(method, "__doc__", py::none());
  if (!doc.is_none()) {
    const std::string text = py::str(doc);
    info.description = text.substr(0, text.find("\n\n"));
  }
  info.make = python_method_factory(method, true);
  info.params = python_method_specs(method);
  info.step_cost = unit_step_cost;  // Python methods run in the package's own process: no server admits them by cost
  info.python = true;
  register_external_method(std::move(info));
  return name;
}

// The runner on a thread of its own while the caller's thread waits without
// the GIL, taking it back every 100 ms to run Python's signal handlers: Ctrl-C
// stops the workers within a step of their runs (those are not stored; the
// same call resumes) and raises KeyboardInterrupt here.
sweep::RunnerOutcome run_interruptibly(const sweep::SweepSpec& spec, const std::vector<sweep::SweepCase>& cases,
                                       storage::RunStore& store, sweep::RunnerOptions options) {
  std::atomic<bool> stop{false};
  options.stop = &stop;
  std::future<sweep::RunnerOutcome> running =
      std::async(std::launch::async, [&] { return sweep::run_sweep(spec, cases, store, options); });
  while (true) {
    {
      py::gil_scoped_release release;  // Python methods take it for their steps
      if (running.wait_for(std::chrono::milliseconds(100)) == std::future_status::ready) break;
    }
    if (PyErr_CheckSignals() != 0) {  // a handler raised (KeyboardInterrupt)
      stop.store(true);
      {
        py::gil_scoped_release release;
        running.wait();
      }
      throw py::error_already_set();
    }
  }
  return running.get();
}

// Runs the spec (JSON text) into the database; returns the report, the
// per-run CSV and what the runner did.
py::tuple run_sweep_spec(const std::string& spec_text, const std::string& spec_dir, const std::string& scenarios_dir,
                         const py::object& jobs_argument, const std::string& db, bool frames) {
  using namespace rrlab::sweep;
  refuse_reentry("rrlab.sweep");
  const int jobs = int(whole_number(jobs_argument, "jobs", 1, 256));
  const SweepSpec spec = parse_sweep_spec(parse_json(spec_text), SpecDirs{spec_dir, scenarios_dir});
  const std::vector<SweepCase> cases = expand_sweep(spec);
  storage::RunStore store(db);
  RunnerOptions options;
  options.jobs = jobs;
  options.frames = frames;
  const RunnerOutcome outcome = run_interruptibly(spec, cases, store, options);
  std::ostringstream csv;
  std::string report;
  {
    py::gil_scoped_release release;
    write_summaries_csv(csv, cases, store.sweep_runs(spec.name));
    report = report_json(build_report(store.sweep_runs(spec.name))).dump();
  }
  py::dict done;
  done["sweep"] = spec.name;
  done["runs"] = outcome.cases;
  done["already_stored"] = outcome.already_stored;
  done["stored"] = outcome.stored;
  done["failures"] = outcome.failures;
  return py::make_tuple(report, csv.str(), done);
}

// A stored run re-simulated from its recorded inputs and compared with its
// stored frames, as `rrlab replay` does; a run of a Python method needs that
// method registered first.
py::object replay_run(const py::object& db_path, const py::object& run_id) {
  refuse_reentry("rrlab.replay");
  const std::int64_t id = whole_number(run_id, "run", 1, kMaxWholeNumber);
  const std::string db = py::str(py::module_::import("os").attr("fspath")(db_path));
  if (!std::filesystem::exists(db)) throw ScenarioError("db", "no database '" + db + "'");
  storage::RunStore store(db);
  const auto run = store.run(id);
  if (!run) throw ScenarioError("run", "no run " + std::to_string(id) + " in " + db);
  storage::ResimulationResult result;
  {
    py::gil_scoped_release release;
    result = storage::resimulate(store, *run, {});
  }
  nlohmann::json out = {{"run", run->id}, {"frames_stored", run->frames}};
  out.update(storage::verification_json(result));
  out["summary"] = summary_to_json(result.summary);
  return py::module_::import("json").attr("loads")(out.dump());
}

}  // namespace

void register_sweeps(py::module_& m) {
  m.def("replay", &replay_run, py::arg("db"), py::arg("run"),
        "Re-simulates a stored run and compares it with its stored frames (rrlab replay): {identical, "
        "frames_compared, first_mismatch, summary, ...}");
  m.def("register_method", &register_method, py::arg("method"),
        "Makes a Python method known by its name to scenarios and sweep specs in this process; returns the name");
  m.def("_run_sweep", &run_sweep_spec, py::arg("spec"), py::arg("spec_dir"), py::arg("scenarios_dir"),
        py::arg("jobs"), py::arg("db"), py::arg("frames"),
        "rrlab.sweep's engine (private): runs a spec (JSON text) into the database `db`; returns (report JSON "
        "text, per-run CSV text, {sweep, runs, stored, already_stored, failures})");
  m.def(
      "generate",
      [](const std::string& family, const py::object& seed_argument, const py::object& count_argument,
         const py::object& first_argument, const py::object& options) {
        // the seeds a sweep spec takes; count: the cases are held in memory; first + count stays an int
        const auto seed = std::uint64_t(whole_number(seed_argument, "seed", 0, kMaxWholeNumber));
        const int count = int(whole_number(count_argument, "count", 1, 100'000));
        const int first = int(whole_number(first_argument, "first", 0, 1'000'000'000));
        const nlohmann::json parsed =
            options.is_none() ? nlohmann::json::object()
                              : parse_json(std::string(py::str(py::module_::import("json").attr("dumps")(options))));
        py::list cases;
        const py::object loads = py::module_::import("json").attr("loads");
        for (int i = 0; i < count; ++i) cases.append(loads(generate_scenario(family, parsed, seed, first + i).dump()));
        return cases;
      },
      py::arg("family"), py::arg("seed") = 1, py::arg("count") = 1, py::arg("first") = 0,
      py::arg("options") = py::none(),
      "Cases of a generated family as scenario documents (dicts, witness included): the cases a sweep entry "
      "{\"generator\": family, \"seed\": seed, \"count\": count, ...options} runs");
}

}  // namespace rrlab::python
