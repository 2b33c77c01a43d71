// Runs a built-in method on a scenario file to the end and prints the summary
// as `rrlab run SCENARIO --method METHOD` does.
//   run_method SCENARIO [METHOD]   (METHOD: the scenario's own when omitted)
#include <rrlab/rrlab.hpp>

#include <exception>
#include <iostream>
#include <memory>

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::cerr << "usage: run_method SCENARIO [METHOD]\n";
    return 2;
  }
  try {
    const rrlab::Scenario scenario = rrlab::load_scenario_file(argv[1]);
    // a method named here runs with its own defaults, not the scenario's parameters
    auto sim = argc == 3 ? std::make_unique<rrlab::Simulator>(scenario, argv[2])
                         : std::make_unique<rrlab::Simulator>(scenario);
    while (!sim->done()) sim->step();
    const rrlab::Summary summary = sim->summary();
    std::cout << rrlab::summary_to_json(summary).dump(2) << "\n";
    return 0;
  } catch (const std::exception& e) {  // a scenario or method name rrlab refuses: the message names it
    std::cerr << "run_method: " << e.what() << "\n";
    return 1;
  }
}
