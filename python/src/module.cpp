// rrlab._rrlab: the engine in-process. Scenarios load as `rrlab run` loads
// them, runs give `rrlab run`'s summary plus its frames as numpy arrays (the
// same numbers bit for bit), a Simulator steps a run and takes the live
// inputs the server takes, and a method may be a Python object
// (python_method.hpp). The GIL is released while the engine steps.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <cstring>
#include <memory>

#include <rrlab/methods/registry.hpp>
#include <rrlab/methods/registry_json.hpp>
#include <rrlab/scenario/scenario.hpp>
#include <rrlab/sim/frame.hpp>
#include <rrlab/sim/run_inputs.hpp>
#include <rrlab/sim/simulator.hpp>

#include "frame_columns.hpp"
#include "method_reentry.hpp"
#include "python_method.hpp"
#include "sweeps.hpp"
#include "whole_number.hpp"

namespace py = pybind11;

namespace rrlab::python {

namespace {

// nlohmann::json <-> Python through the json module: exact for numbers
// (shortest round-trip text), and rare enough not to matter for speed.
py::object to_python(const nlohmann::json& value) {
  return py::module_::import("json").attr("loads")(value.dump());
}

nlohmann::json from_python(const py::handle& value, const std::string& what) {
  try {
    // numpy arrays and scalars through their tolist()
    const py::object text = py::module_::import("json").attr("dumps")(
        value, py::arg("default") = py::module_::import("rrlab.errors").attr("jsonable"));
    return nlohmann::json::parse(std::string(py::str(text)));
  } catch (const nlohmann::json::exception&) {
    throw ScenarioError(what, "not representable as JSON");
  } catch (const py::error_already_set& e) {
    throw ScenarioError(what, std::string("not representable as JSON: ") + e.what());
  }
}

// A scenario from a Scenario, a dict, a JSON text or a file path.
Scenario scenario_of(const py::object& source) {
  if (py::isinstance<Scenario>(source)) return source.cast<Scenario>();
  if (py::isinstance<py::dict>(source)) return parse_scenario(from_python(source, "scenario"), ".");
  const std::string text = py::str(py::module_::import("os").attr("fspath")(source));
  const size_t first = text.find_first_not_of(" \t\r\n");
  if (first != std::string::npos && text[first] == '{') return parse_scenario_text(text);
  return load_scenario_file(text);
}

// A parameter of the simulator's method: for a Python method object the run
// was given (`python_method`, its name; empty when none), a number checked
// against that object's specs; else a number or an enumeration label resolved
// as a scenario file's (built-in and registered methods).
void set_method_param(Simulator& sim, const std::string& python_method, const std::string& name,
                      const py::handle& value) {
  const std::string path = "params." + name;
  if (python_method.empty() || sim.method_name() != python_method) {
    const auto [resolved, number] = resolve_method_param(sim.method_name(), name, from_python(value, path), path);
    sim.set_param(resolved, number);
    return;
  }
  if (py::isinstance<py::str>(value) || py::isinstance<py::bool_>(value)) throw ScenarioError(path, "expected a number");
  double number = 0;
  try {
    number = py::float_(py::reinterpret_borrow<py::object>(value));
  } catch (py::error_already_set&) {
    throw ScenarioError(path, "expected a number");
  }
  sim.set_param(name, number);
}

// A simulator of `scenario` with `method` (None: the scenario's; a name; or a
// Python method object, whose name goes to `python_method`) and `params` (a
// dict: numbers, or enumeration labels of built-in methods).
std::unique_ptr<Simulator> make_simulator(const Scenario& scenario, const py::object& method, const py::object& params,
                                          std::string& python_method) {
  std::unique_ptr<Simulator> sim;
  python_method.clear();
  if (method.is_none()) {
    sim = std::make_unique<Simulator>(scenario);
  } else if (py::isinstance<py::str>(method)) {
    const std::string name = method.cast<std::string>();
    require_method(name, "method");
    // the scenario's parameters belong to its own method (as `rrlab run --method`)
    sim = name == scenario.method.name ? std::make_unique<Simulator>(scenario) : std::make_unique<Simulator>(scenario, name);
  } else {
    python_method = python_method_name(method);
    sim = std::make_unique<Simulator>(scenario, python_method, python_method_factory(method));
  }
  if (!params.is_none()) {
    if (!py::isinstance<py::dict>(params)) throw ScenarioError("params", "expected a dict of parameter values");
    for (const auto& [key, value] : params.cast<py::dict>())
      set_method_param(*sim, python_method, py::str(key), value);
  }
  return sim;
}

py::array column_array(const FrameColumn& column, long frames) {
  std::vector<py::ssize_t> shape{frames};
  if (column.width > 1) shape.push_back(column.width);
  const size_t count = column.values.size();
  if (column.type == FrameColumn::real) {
    py::array_t<double> out(shape);
    if (count) std::memcpy(out.mutable_data(), column.values.data(), count * sizeof(double));
    return out;
  }
  if (column.type == FrameColumn::flag) {
    py::array_t<bool> out(shape);
    bool* data = out.mutable_data();
    for (size_t i = 0; i < count; ++i) data[i] = column.values[i] != 0.0;
    return out;
  }
  py::array_t<std::int64_t> out(shape);
  std::int64_t* data = out.mutable_data();
  for (size_t i = 0; i < count; ++i) data[i] = std::int64_t(column.values[i]);
  return out;
}

py::dict frames_dict(const FrameColumns& columns) {
  py::dict frames, diagnostics;
  for (const FrameColumn& column : columns.columns())
    (column.diagnostic ? diagnostics : frames)[py::str(column.name)] = column_array(column, columns.frames());
  frames["diagnostics"] = diagnostics;
  return frames;
}

long checked_steps(const py::object& steps, long otherwise) {
  return steps.is_none() ? otherwise : long(whole_number(steps, "steps", 1, ScenarioLimits::max_steps));
}

// Every frame of a run is kept for its arrays: a run whose frames would
// outgrow this is refused before it starts (Simulator.step has no such bound).
constexpr double kMaxFrameBytes = 1 << 30;

void check_frame_memory(const FrameColumns& columns, long steps) {
  long per_frame = 0;
  for (const FrameColumn& column : columns.columns()) per_frame += column.width;
  const double bytes = double(steps) * double(per_frame) * sizeof(double);
  if (bytes > kMaxFrameBytes)
    throw ScenarioError("steps", std::to_string(steps) + " steps of " + std::to_string(per_frame) +
                                     " numbers per frame exceed the 1 GiB the frames may take (at most " +
                                     std::to_string(long(kMaxFrameBytes / (double(per_frame) * sizeof(double)))) +
                                     " steps; Simulator.step runs longer without keeping frames)");
}

// Steps with the GIL released (a Python method takes it back for its step),
// taking it back every few hundred steps so that Ctrl-C (KeyboardInterrupt)
// stops a long run.
void step_without_gil(Simulator& sim, long count, Recorder* recorder) {
  constexpr long kStepsBetweenSignalChecks = 256;
  long done = 0;
  while (done < count && !sim.done()) {
    {
      py::gil_scoped_release release;
      for (long i = 0; i < kStepsBetweenSignalChecks && done < count && !sim.done(); ++i, ++done) {
        timed_step(sim);
        if (recorder) recorder->frame(sim.frame());
      }
    }
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  }
}

// The Python Simulator: a run stepped from Python, with the server's live
// inputs. One thread at a time: a call while another thread is inside it
// (stepping without the GIL) raises instead of racing.
struct PySimulator {
  std::unique_ptr<Simulator> sim;
  std::string python_method;  // the Python method object's name, if it was given one
  mutable std::atomic<bool> busy{false};  // read-only calls mark it too

  class Use {
   public:
    explicit Use(const PySimulator& s) : flag_(s.busy) {
      if (flag_.exchange(true)) throw std::runtime_error("this Simulator is busy stepping (in another thread, or this call comes from its method's step)");
    }
    ~Use() { flag_.store(false); }
    Use(const Use&) = delete;
    Use& operator=(const Use&) = delete;

   private:
    std::atomic<bool>& flag_;
  };

  void apply(const std::string& kind, const py::object& payload) {
    // a Python method object is not in the registry: its parameters and a
    // switch back to it are applied here, the other inputs as the server does
    if (!python_method.empty() && kind == "params" && py::isinstance<py::dict>(payload)) {
      const Use use(*this);
      for (const auto& [key, value] : payload.cast<py::dict>()) set_method_param(*sim, python_method, py::str(key), value);
      return;
    }
    if (!python_method.empty() && kind == "method" && py::isinstance<py::dict>(payload) &&
        payload.cast<py::dict>().contains("name") && py::str(payload["name"]).cast<std::string>() == python_method) {
      const py::dict input = payload.cast<py::dict>();
      for (const auto& [key, value] : input)
        if (py::str(key).cast<std::string>() != "name" && py::str(key).cast<std::string>() != "params")
          throw ScenarioError(py::str(key).cast<std::string>(), "unknown key (known: name, params)");
      const Use use(*this);
      sim->switch_method(python_method);
      if (input.contains("params")) {
        if (!py::isinstance<py::dict>(input["params"])) throw ScenarioError("params", "expected a dict");
        for (const auto& [key, value] : input["params"].cast<py::dict>())
          set_method_param(*sim, python_method, py::str(key), value);
      }
      return;
    }
    const nlohmann::json input = payload.is_none() ? nlohmann::json::object() : from_python(payload, kind);
    const Use use(*this);
    apply_input(*sim, kind, input);
  }

  py::dict frame() const {
    const Use use(*this);
    FrameColumns one;
    one.begin(*sim);
    one.frame(sim->frame());
    py::dict out = frames_dict(one);
    py::dict row;
    for (const auto& [key, value] : out) {
      if (std::string(py::str(key)) == "diagnostics") {
        py::dict diag;
        for (const auto& [name, column] : value.cast<py::dict>()) diag[name] = column.cast<py::array>()[py::int_(0)];
        row[key] = diag;
      } else {
        row[key] = value.cast<py::array>()[py::int_(0)];
      }
    }
    return row;
  }
};

// The engine's exceptions as rrlab.errors' classes, all rrlab.Error (and each
// the built-in exception pybind11 would have raised: ValueError, RuntimeError),
// so that `except rrlab.Error` catches whatever rrlab raises. pybind11's own
// (a Python error passing through, a failed cast) and running out of memory
// stay what they are.
void translate_errors() {
  py::register_exception_translator([](std::exception_ptr error) {
    if (!error) return;
    const py::module_ errors = py::module_::import("rrlab.errors");
    auto raise = [&](const char* type, py::object instance) {
      PyErr_SetObject(errors.attr(type).ptr(), instance.ptr());
    };
    try {
      std::rethrow_exception(error);
    } catch (const ScenarioError& e) {
      raise("ScenarioError", errors.attr("ScenarioError")(e.what(), e.path()));
    } catch (const ParamError& e) {
      raise("ParamError", errors.attr("ParamError")(e.what(), e.param()));  // the message names the parameter
    } catch (const MethodError& e) {
      raise("MethodError", errors.attr("MethodError")(e.what()));
    } catch (const InputStateError& e) {
      raise("InputStateError", errors.attr("InputStateError")(e.what()));
    } catch (const py::builtin_exception&) {
      throw;  // pybind11's translator raises these
    } catch (const std::bad_alloc&) {
      throw;  // MemoryError
    } catch (const std::invalid_argument& e) {
      raise("ArgumentError", errors.attr("ArgumentError")(e.what()));
    } catch (const std::exception& e) {
      raise("EngineError", errors.attr("EngineError")(e.what()));
    }
  });
}

}  // namespace

}  // namespace rrlab::python

PYBIND11_MODULE(_rrlab, m) {
  using namespace rrlab;
  using namespace rrlab::python;
  m.doc() = "rrlab's engine (the rrlab package wraps it: import rrlab)";
  m.attr("__version__") = RRLAB_VERSION;
  translate_errors();
  register_step_state(m);
  register_sweeps(m);

  py::class_<Scenario>(m, "Scenario", "A loaded, validated scenario (rrlab.load_scenario)")
      .def_property_readonly("name", [](const Scenario& s) { return s.name; }, "the scenario's name")
      .def_property_readonly("dof", [](const Scenario& s) { return s.model.dof(); }, "the robot's number of joints n")
      .def_property_readonly("dt", [](const Scenario& s) { return s.dt; }, "step length (s)")
      .def_property_readonly("duration", [](const Scenario& s) { return s.duration; }, "the run's length (s)")
      .def_property_readonly("steps", [](const Scenario& s) { return s.steps(); }, "steps in a run: duration / dt")
      .def_property_readonly(
          "task_space", [](const Scenario& s) { return std::string(to_string(s.task.space)); },
          "the task's space: xy, xyz or pose")
      .def_property_readonly("method", [](const Scenario& s) { return s.method.name; }, "the scenario's method's name")
      .def_property_readonly(
          "params",
          [](const Scenario& s) {
            py::dict out;
            for (const auto& [name, value] : s.method.params) out[py::str(name)] = value;
            return out;
          },
          "the parameters the scenario sets for its method, by name (numbers)")
      .def_property_readonly(
          "q0", [](const Scenario& s) { return Eigen::VectorXd(s.q0); }, "the initial joint positions (n,)")
      .def("__repr__", [](const Scenario& s) {
        return "<rrlab.Scenario " + s.name + ": " + std::to_string(s.model.dof()) + " joints, " +
               to_string(s.task.space) + " task, " + std::to_string(s.steps()) + " steps, method " + s.method.name + ">";
      });

  m.def("load_scenario", &scenario_of, py::arg("source"),
        "A scenario from a file path, a dict or a JSON string; bad input raises rrlab.ScenarioError naming the JSON "
        "path");
  m.def("methods", [] { return to_python(methods_json()); }, "The built-in methods with their parameter specs");
  m.def(
      "run",
      [](const py::object& scenario, const py::object& method, const py::object& params, const py::object& steps) {
        refuse_reentry("rrlab.run");
        std::string python_method;
        std::unique_ptr<Simulator> sim = make_simulator(scenario_of(scenario), method, params, python_method);
        sim->set_total_steps(checked_steps(steps, sim->total_steps()));
        FrameColumns columns;
        columns.begin(*sim);
        check_frame_memory(columns, sim->total_steps());
        step_without_gil(*sim, sim->total_steps(), &columns);
        py::dict out = to_python(summary_to_json(sim->summary()));
        out["frames"] = frames_dict(columns);
        return out;
      },
      py::arg("scenario"), py::arg("method") = py::none(), py::arg("params") = py::none(),
      py::arg("steps") = py::none(),
      "Runs to the end: rrlab run's summary keys plus 'frames', every column of its CSV as numpy arrays");

  py::class_<PySimulator>(m, "Simulator", "A run stepped from Python")
      .def(py::init([](const py::object& scenario, const py::object& method, const py::object& params) {
             auto s = std::make_unique<PySimulator>();
             s->sim = make_simulator(scenario_of(scenario), method, params, s->python_method);
             return s;
           }),
           py::arg("scenario"), py::arg("method") = py::none(), py::arg("params") = py::none(),
           "A run of `scenario` (a Scenario, a file path, a dict or a JSON string) with `method` (None: the "
           "scenario's own with its parameters; a built-in method's name, from its defaults; or a Python method "
           "object) and `params` (a dict of numbers, or labels for enumerations), before its first step")
      .def(
          "step",
          [](PySimulator& s, const py::object& count) {
            refuse_reentry("Simulator.step");
            const long steps = long(whole_number(count, "count", 0, kMaxWholeNumber));
            const PySimulator::Use use(s);
            step_without_gil(*s.sim, steps, nullptr);
          },
          py::arg("count") = 1, "Advances `count` steps (fewer at the end of the run)")
      .def_property_readonly(
          "done",
          [](const PySimulator& s) {
            const PySimulator::Use use(s);
            return s.sim->done();
          },
          "True once the run has taken all its steps (step() then does nothing)")
      .def_property_readonly(
          "method",
          [](const PySimulator& s) {
            const PySimulator::Use use(s);
            return s.sim->method_name();
          },
          "the name of the method that steps the run now")
      .def_property_readonly(
          "params",
          [](const PySimulator& s) {
            const PySimulator::Use use(s);
            return to_python(param_values_json(s.sim->method()));
          },
          "the method's current parameter values, by name (enumerations as labels)")
      .def_property_readonly("state",
                             [](const PySimulator& s) {
                               const PySimulator::Use use(s);
                               py::dict out;
                               out["t"] = s.sim->state().t;
                               out["step"] = s.sim->state().step;
                               out["q"] = Eigen::VectorXd(s.sim->state().q);
                               out["qdot"] = Eigen::VectorXd(s.sim->state().qdot);
                               return out;
                             },
                             "the state the next step starts from: t, step, q, qdot")
      .def_property_readonly("frame", &PySimulator::frame, "the last step's frame (the CSV's columns)")
      .def(
          "summary",
          [](const PySimulator& s) {
            const PySimulator::Use use(s);
            return to_python(summary_to_json(s.sim->summary()));
          },
          "The run's summary so far: the keys of rrlab run's (steps, max_tracking_error, collided, final_q, ...)")
      .def("apply", &PySimulator::apply, py::arg("kind"), py::arg("payload") = py::none(),
           "A live input as the server takes it: params, obstacle, obstacle_add, obstacle_remove, joystick, method, "
           "reset (docs/api.md)")
      .def(
          "set_param",
          [](PySimulator& s, const std::string& name, const py::object& value) {
            const PySimulator::Use use(s);
            set_method_param(*s.sim, s.python_method, name, value);
          },
          py::arg("name"), py::arg("value"),
          "Sets a parameter of the method: a number, or a label for an enumeration; out of range raises "
          "rrlab.ScenarioError (rrlab.ParamError for a Python method's)")
      .def(
          "move_obstacle",
          [](PySimulator& s, const std::string& id, const py::object& position, const py::object& velocity) {
            py::dict payload;
            payload["id"] = id;
            if (!position.is_none()) payload["position"] = position;
            if (!velocity.is_none()) payload["velocity"] = velocity;
            s.apply("obstacle", payload);
          },
          py::arg("id"), py::arg("position") = py::none(), py::arg("velocity") = py::none(),
          "Moves obstacle `id` to `position` now and/or gives it a constant `velocity` (m/s): "
          "apply(\"obstacle\", {...})")
      .def(
          "joystick",
          [](PySimulator& s, const py::object& linear, const py::object& angular) {
            py::dict payload;
            payload["linear"] = linear;
            if (!angular.is_none()) payload["angular"] = angular;
            s.apply("joystick", payload);
          },
          py::arg("linear"), py::arg("angular") = py::none(),
          "Velocity command to a joystick task: `linear` [vx, vy(, vz)] m/s, `angular` rad/s (pose tasks); held "
          "until the next. rrlab.InputStateError when the task is not a joystick")
      .def(
          "reset", [](PySimulator& s) { s.apply("reset", py::none()); },
          "Starts the run over from its first step, with the method's current parameters");
}
