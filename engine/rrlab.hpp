// The engine in one header: scenarios, the simulator, its summary and the
// method registry. What an out-of-tree project builds on
// (find_package(rrlab) and rrlab::engine; docs/cpp.md):
//
//   rrlab::Scenario scenario = rrlab::load_scenario_file("scenario.json");
//   rrlab::Simulator sim(scenario, "dls");  // the method with its defaults
//   while (!sim.done()) sim.step();
//   rrlab::Summary summary = sim.summary();
//
// A method of one's own is a subclass of rrlab::Method registered with
// rrlab::register_external_method (examples/cpp/own_method.cpp).
#pragma once

#include <rrlab/methods/method.hpp>
#include <rrlab/methods/registry.hpp>
#include <rrlab/methods/step_cost.hpp>
#include <rrlab/scenario/scenario.hpp>
#include <rrlab/sim/frame.hpp>
#include <rrlab/sim/simulator.hpp>
