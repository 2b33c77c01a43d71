// The run-record loader of `rrlab run RECORD.json` (cli/run.cpp): a
// record (or a plain scenario), its simulator, and every recorded event applied.
#include <limits>

#include <rrlab/sim/run_record.hpp>
#include <rrlab/sim/simulator.hpp>
#include <rrlab/util/nesting_depth.hpp>

#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  nlohmann::json doc;
  try {
    doc = rrlab::parse_json(rrlab::fuzz::as_text(data, size));
  } catch (const std::exception&) {
    return 0;  // not JSON, or nested too deep: read_json_file's ScenarioError
  }
  rrlab::fuzz::expect_documented("parse_run_record", [&] {
    rrlab::RunRecordDoc input;
    if (rrlab::is_run_record(doc))
      input = rrlab::parse_run_record(doc);
    else
      input.scenario = rrlab::parse_scenario(doc);
    rrlab::Simulator sim(input.scenario);
    rrlab::EventReplayer events(input.events);
    events.apply_due(sim, std::numeric_limits<long>::max());
  });
  return 0;
}
