// A redundancy-resolution method written in Python (a subclass of
// rrlab.Method): its parameters become the engine's ParamSpecs, and each step
// the engine calls its step(state) with the GIL held and takes the returned
// joint velocity through the same integration, checks and metrics as a
// built-in method's. A wrong shape, a non-finite value or an exception raised
// in step() stops the run with a MethodError naming the method and the step.
#pragma once

#include <pybind11/pybind11.h>

#include <stdexcept>
#include <string>
#include <vector>

#include <rrlab/sim/simulator.hpp>

namespace rrlab::python {

class MethodError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The method's name (its `name` attribute, else its class name), checked to
// be a name no built-in method has.
std::string python_method_name(const pybind11::object& method);

// Its parameters (the `params` list of rrlab.Param) as the engine's specs;
// std::invalid_argument for a bad one.
std::vector<ParamSpec> python_method_specs(const pybind11::object& method);

// Builds the engine's adapter for `method` on every (re)start of a run: on
// `method` itself (a run from Python: the caller's object sees its run), or,
// copy_per_run, on a deep copy per run (a sweep: runs on several threads
// keep their parameters and state apart).
MethodFactory python_method_factory(pybind11::object method, bool copy_per_run = false);

// The state class Python methods receive (registered on the module).
void register_step_state(pybind11::module_& m);

}  // namespace rrlab::python
