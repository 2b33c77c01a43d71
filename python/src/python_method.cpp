#include "python_method.hpp"

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>

#include <cmath>
#include <memory>
#include <sstream>

#include <rrlab/methods/registry.hpp>

#include "method_reentry.hpp"

namespace py = pybind11;

namespace rrlab::python {

namespace {

// What a Python method sees at one step, read through properties that copy
// into new numpy arrays (a method pays only for what it reads). Valid during
// its step() only: the engine's buffers move on with the next step.
class StepState {
 public:
  const StepInput& in() const {
    if (!in_) throw std::runtime_error("this state belongs to a step that has ended (keep copies, not the state)");
    return *in_;
  }
  void bind(const StepInput* in) { in_ = in; }

  // Per link, its nearest obstacle pair (-1: no obstacle).
  int nearest(int link) const { return in().distances.nearest_obstacle(link); }
  int links() const { return in().model.link_count(); }

  Eigen::MatrixXd link_rows(Eigen::Vector3d LinkObstacleDistance::*member) const {
    Eigen::MatrixXd rows = Eigen::MatrixXd::Constant(links(), 3, std::nan(""));
    for (int l = 0; l < links(); ++l)
      if (const int o = nearest(l); o >= 0) rows.row(l) = (in().distances.at(l, o).*member).transpose();
    return rows;
  }

 private:
  const StepInput* in_ = nullptr;
};

// Releases a Python object with the GIL held, whoever drops the last
// reference; after the interpreter has ended (a registered method's factory
// lives in a static table) there is nothing left to release.
std::shared_ptr<py::object> held(py::object object) {
  return std::shared_ptr<py::object>(new py::object(std::move(object)), [](py::object* o) {
    if (!Py_IsInitialized()) {
      o->release();  // the interpreter is gone: drop the handle without touching it
      delete o;
      return;
    }
    py::gil_scoped_acquire gil;
    delete o;
  });
}

// A number attribute of a Param, or an error naming it.
double param_number(const py::handle& param, const char* key, const std::string& path) {
  try {
    return py::float_(param.attr(key));
  } catch (py::error_already_set&) {
    throw std::invalid_argument(path + "." + key + ": must be a number");
  }
}

std::vector<ParamSpec> specs_of(const py::object& method, const std::string& name) {
  std::vector<ParamSpec> specs;
  if (!py::hasattr(method, "params")) return specs;
  const py::object params = method.attr("params");
  if (!py::isinstance<py::list>(params) && !py::isinstance<py::tuple>(params))
    throw std::invalid_argument(name + ".params: must be a list of rrlab.Param");
  for (const py::handle p : params) {
    if (!py::hasattr(p, "name") || !py::isinstance<py::str>(p.attr("name")))
      throw std::invalid_argument(name + ".params: each entry must be an rrlab.Param with a name");
    ParamSpec spec;
    spec.name = py::str(p.attr("name"));
    const std::string path = name + ".params." + spec.name;
    spec.def = param_number(p, "default", path);
    spec.min = param_number(p, "min", path);
    spec.max = param_number(p, "max", path);
    spec.step = param_number(p, "step", path);
    spec.label = py::str(py::getattr(p, "label", py::str("")));
    spec.unit = py::str(py::getattr(p, "unit", py::str("")));
    spec.help = py::str(py::getattr(p, "help", py::str("")));
    if (spec.name.empty()) throw std::invalid_argument(name + ".params: a parameter without a name");
    if (find_param(specs, spec.name) >= 0) throw std::invalid_argument(path + ": listed twice");
    if (!(spec.min <= spec.max)) throw std::invalid_argument(path + ": min above max");
    if (const std::string problem = param_problem(spec, spec.def); !problem.empty())
      throw std::invalid_argument(path + ": default " + problem);
    specs.push_back(std::move(spec));
  }
  return specs;
}

class PythonMethod final : public Method {
 public:
  PythonMethod(std::shared_ptr<py::object> object, std::string name, std::vector<ParamSpec> specs,
               const MethodContext& ctx)
      : Method(std::move(specs)),
        object_(std::move(object)),
        name_(std::move(name)),
        where_("the Python method " + name_),
        dof_(ctx.model.dof()),
        context_{ctx.model.dof(), task_rows(ctx.space), ctx.obstacle_count, ctx.seed} {
    py::gil_scoped_acquire gil;
    step_ = held(object_->attr("step"));
    values_ = held(py::dict());
    publish_params();
  }

  void step(const StepInput& in, StepOutput& out) override {
    py::gil_scoped_acquire gil;
    const InMethodCode in_method(where_);  // its start() and step() may not run a simulation
    std::ostringstream where;
    where << name_ << " at step " << in.state.step << " (t = " << in.state.t << " s)";
    // this run's parameter values, whoever else shares the object (two Simulators of one method object)
    if (py::getattr(*object_, "param_values", py::none()).ptr() != values_->ptr())
      object_->attr("param_values") = *values_;
    if (!started_) {  // start() after the run's parameters are set, before its first step
      started_ = true;
      if (py::hasattr(*object_, "start")) {
        py::dict context;
        context["dof"] = context_.dof;
        context["task_rows"] = context_.task_rows;
        context["obstacles"] = context_.obstacles;
        context["seed"] = context_.seed;
        call(name_ + " in start()", nullptr, [&] { object_->attr("start")(context); });
      }
    }
    // a state of its own each step: one kept from an earlier step raises instead of showing this one
    const auto state = std::make_shared<StepState>();
    state->bind(&in);
    py::object result;
    call(where.str(), state.get(), [&] { result = (*step_)(py::cast(state)); });
    state->bind(nullptr);
    const auto qdot = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(result);
    if (!qdot)
      throw MethodError(where.str() + ": step() returned " + std::string(py::str(py::type::of(result).attr("__name__"))) +
                        ", not an array of " + std::to_string(dof_) + " joint velocities");
    if (qdot.ndim() != 1 || qdot.shape(0) != dof_) {
      std::string shape = "(";
      for (py::ssize_t d = 0; d < qdot.ndim(); ++d) shape += (d ? ", " : "") + std::to_string(qdot.shape(d));
      throw MethodError(where.str() + ": step() returned shape " + shape + (qdot.ndim() == 1 ? ",)" : ")") +
                        ", expected (" + std::to_string(dof_) + ",)");
    }
    for (int i = 0; i < dof_; ++i) {
      if (!std::isfinite(qdot.at(i)))
        throw MethodError(where.str() + ": step() returned " + (std::isnan(qdot.at(i)) ? "NaN" : "an infinite value") +
                          " for joint " + std::to_string(i + 1));
      out.qdot[i] = qdot.at(i);
    }
  }

 private:
  void on_param_changed(ParamSlot) override {
    py::gil_scoped_acquire gil;
    publish_params();
  }

  // The current values as the object's `param_values` dict (rrlab.Method.param reads it).
  void publish_params() {
    py::dict values;
    for (size_t i = 0; i < specs().size(); ++i) values[py::str(specs()[i].name)] = param_values()[Eigen::Index(i)];
    *values_ = values;
    object_->attr("param_values") = values;
  }

  // Runs a call into Python; an exception it raises becomes a MethodError
  // saying where, but Ctrl-C (KeyboardInterrupt) stays what it is.
  template <typename Call>
  void call(const std::string& where, StepState* state, Call&& body) {
    try {
      body();
    } catch (py::error_already_set& e) {
      if (state) state->bind(nullptr);
      if (e.matches(PyExc_KeyboardInterrupt)) throw;
      throw MethodError(where + ": " + e.what());
    }
  }

  struct Context {
    int dof, task_rows, obstacles;
    std::uint64_t seed;
  };

  std::shared_ptr<py::object> object_, step_, values_;
  std::string name_, where_;
  int dof_;
  Context context_;
  bool started_ = false;
};

}  // namespace

std::string python_method_name(const py::object& method) {
  if (py::isinstance<py::type>(method))
    throw std::invalid_argument("method: an instance is needed (" +
                                std::string(py::str(method.attr("__name__"))) + "(), not the class)");
  if (!py::hasattr(method, "step") || !PyCallable_Check(method.attr("step").ptr()))
    throw std::invalid_argument("method: expected a method name or an rrlab.Method with a step(state) method");
  const py::object named = py::getattr(method, "name", py::none());
  if (!named.is_none() && !py::isinstance<py::str>(named)) throw std::invalid_argument("method.name: must be a string");
  const std::string name = named.is_none() ? std::string(py::str(py::type::of(method).attr("__name__")))
                                           : std::string(py::str(named));
  if (name.empty()) throw std::invalid_argument("method.name: empty");
  if (const MethodInfo* known = find_method(name); known && !known->python)
    throw std::invalid_argument("method.name: \"" + name + "\" is a built-in method's name; choose another");
  return name;
}

std::vector<ParamSpec> python_method_specs(const py::object& method) {
  return specs_of(method, python_method_name(method));
}

MethodFactory python_method_factory(py::object method, bool copy_per_run) {
  const std::string name = python_method_name(method);
  std::vector<ParamSpec> specs = specs_of(method, name);
  std::shared_ptr<py::object> object = held(std::move(method));
  return [object, name, specs, copy_per_run](const MethodContext& ctx) -> std::unique_ptr<Method> {
    if (!copy_per_run) return std::make_unique<PythonMethod>(object, name, specs, ctx);
    py::gil_scoped_acquire gil;  // a sweep's worker thread
    const std::string where = "the copy of the Python method " + name;
    const InMethodCode in_method(where);  // a __deepcopy__ is the method's code too
    std::shared_ptr<py::object> copy;
    try {
      copy = held(py::module_::import("copy").attr("deepcopy")(*object));
    } catch (py::error_already_set& e) {
      throw MethodError(name + ": a sweep runs a copy of the method object per run, and copy.deepcopy failed: " +
                        e.what());
    }
    return std::make_unique<PythonMethod>(copy, name, specs, ctx);
  };
}

void register_step_state(py::module_& m) {
  using S = StepState;
  py::class_<S, std::shared_ptr<S>>(m, "StepState",
                                    "What a Python method's step() sees (valid during that call; arrays are copies)")
      .def_property_readonly("t", [](const S& s) { return s.in().state.t; }, "time at the start of the step (s)")
      .def_property_readonly("step", [](const S& s) { return s.in().state.step; }, "step index")
      .def_property_readonly("dt", [](const S& s) { return s.in().dt; }, "step length (s)")
      .def_property_readonly("q", [](const S& s) { return Eigen::VectorXd(s.in().state.q); }, "joint positions (n,)")
      .def_property_readonly("qdot", [](const S& s) { return Eigen::VectorXd(s.in().state.qdot); },
                             "joint velocities applied over the previous step (n,)")
      .def_property_readonly("J", [](const S& s) { return Eigen::MatrixXd(s.in().task_jacobian); },
                             "task Jacobian (m, n): the rows of the task space (xy 2, xyz 3, pose 6)")
      .def_property_readonly("xdot", [](const S& s) { return Eigen::VectorXd(s.in().ref.xdot); },
                             "task velocity command (m,): feed-forward plus gain times error, as built-in methods get")
      .def_property_readonly("xdot_ff", [](const S& s) { return Eigen::VectorXd(s.in().ref.xdot_ff); },
                             "feed-forward task velocity (m,)")
      .def_property_readonly("error", [](const S& s) { return Eigen::VectorXd(s.in().ref.error); },
                             "task error, desired minus actual (m,); orientation rows as a rotation vector")
      .def_property_readonly("target", [](const S& s) { return Eigen::Vector3d(s.in().ref.position); },
                             "desired end-effector position at t (3,)")
      .def_property_readonly("ee", [](const S& s) { return Eigen::Vector3d(s.in().kin.end_effector().translation()); },
                             "end-effector position (3,)")
      .def_property_readonly("ee_rotation",
                             [](const S& s) { return Eigen::Matrix3d(s.in().kin.end_effector().linear()); },
                             "end-effector orientation (3, 3)")
      .def_property_readonly("q_lower", [](const S& s) { return Eigen::VectorXd(s.in().model.limits.lower); },
                             "joint position lower limits (n,), -inf where unbounded")
      .def_property_readonly("q_upper", [](const S& s) { return Eigen::VectorXd(s.in().model.limits.upper); },
                             "joint position upper limits (n,), inf where unbounded")
      .def_property_readonly("qdot_max", [](const S& s) { return Eigen::VectorXd(s.in().model.limits.velocity); },
                             "joint speed limits (n,), inf where unbounded")
      .def_property_readonly("qddot_max",
                             [](const S& s) { return Eigen::VectorXd(s.in().model.limits.acceleration); },
                             "joint acceleration limits (n,), inf where unbounded")
      .def_property_readonly(
          "distances",
          [](const S& s) {
            Eigen::VectorXd d = Eigen::VectorXd::Constant(s.links(), std::numeric_limits<double>::infinity());
            for (int l = 0; l < s.links(); ++l)
              if (const int o = s.nearest(l); o >= 0) d[l] = s.in().distances.at(l, o).distance;
            return d;
          },
          "per link, the signed distance to its nearest obstacle (links,), inf without obstacles")
      .def_property_readonly("link_points", [](const S& s) { return s.link_rows(&LinkObstacleDistance::on_link); },
                             "per link, its point nearest that obstacle (links, 3), NaN without one")
      .def_property_readonly("obstacle_points",
                             [](const S& s) { return s.link_rows(&LinkObstacleDistance::on_obstacle); },
                             "per link, the obstacle's nearest point (links, 3)")
      .def_property_readonly("normals", [](const S& s) { return s.link_rows(&LinkObstacleDistance::normal); },
                             "per link, the unit direction from the obstacle to the link (links, 3)")
      .def_property_readonly(
          "distance_jacobians",
          [](const S& s) {
            const StepInput& in = s.in();
            const int n = in.model.dof();
            py::array_t<double> out({s.links(), 3, n});
            auto view = out.mutable_unchecked<3>();
            Eigen::MatrixXd jac(3, n);
            for (int l = 0; l < s.links(); ++l) {
              const int o = s.nearest(l);
              if (o >= 0) point_jacobian_linear(in.model, in.kin, l, in.distances.at(l, o).on_link, jac);
              for (int r = 0; r < 3; ++r)
                for (int c = 0; c < n; ++c) view(l, r, c) = o >= 0 ? jac(r, c) : std::nan("");
            }
            return out;
          },
          "per link, the linear Jacobian of its nearest point (links, 3, n): normals[l] @ it is the distance's gradient")
      .def_property_readonly(
          "manipulability",
          [](const S& s) {
            const Eigen::MatrixXd& j = s.in().task_jacobian;
            return std::sqrt(std::max(0.0, (j * j.transpose()).determinant()));
          },
          "Yoshikawa's sqrt(det(J J^T))");
}

}  // namespace rrlab::python
