// The scenario parser on arbitrary text, then the simulator built from what it
// accepts (as POST /api/scenarios/validate and `rrlab run` do).
#include <rrlab/scenario/scenario.hpp>
#include <rrlab/sim/simulator.hpp>

#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rrlab::fuzz::expect_documented("parse_scenario_text", [&] {
    const rrlab::Scenario scenario = rrlab::parse_scenario_text(rrlab::fuzz::as_text(data, size));
    rrlab::Simulator check(scenario);
  });
  return 0;
}
