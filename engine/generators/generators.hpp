// Seeded families of generated scenarios for sweeps. A call returns a
// scenario JSON document (what a scenario file holds, with a name such as
// "planar_clutter-17"), so a generated case is stored with its run and
// reproduces from its record without the generator.
// Guarantees, for every family and every index: the case carries a witness
// (a joint trajectory, "witness" in the document) that the engine plays back
// without collision, inside the limits, tracking the path within 0.5 mm: the
// path is the witness's hand trace and every obstacle keeps the clearance
// from the witness arm at every step (generator_witness.hpp).
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace rrlab {

struct GeneratorCase;  // generator_case.hpp

// One row per family, in the order every list shows them: the CLI's help,
// the OpenAPI enum of a sweep's "generator", the report scripts (through
// `rrlab generate --list`) and the tests take the families from here.
// Adding a family: its generator_<family>.cpp, a row here, its section of
// docs/generators.md.
struct GeneratorFamily {
  std::string name;
  std::string summary;                                  // one line: what its cases are
  nlohmann::json (*generate)(GeneratorCase&) = nullptr;  // one case (generator_case.hpp)
  // "<family>_open": the family's cases with no obstacle placed to block the
  // minimum-norm solution (its generator with GeneratorCase::open)
  bool open = false;
};
const std::vector<GeneratorFamily>& generator_family_table();

// The families' names, in the table's order: planar_clutter, planar_limits,
// narrow_passage, spatial_clutter, moving_obstacles, urdf_tabletop, urdf_shelf,
// then the obstacle families' _open variants in the same order.
const std::vector<std::string>& generator_families();

// Case `index` of `family` under `seed` with the family's options (DOF range,
// obstacle count, path length, speed, ...; missing keys take the documented
// defaults). The same (family, options, seed, index) always gives the same
// document. Throws ScenarioError naming the option (path "options.<key>";
// "generator" for an unknown family or when no case met the family's
// conditions within its bounded attempts; "index" for a negative index).
// Families and options: docs/generators.md.
nlohmann::json generate_scenario(const std::string& family, const nlohmann::json& options, std::uint64_t seed,
                                 int index);

// The family's options alone, without generating a case (a case can take
// tens of milliseconds): throws the ScenarioError generate_scenario() would
// for an unknown family or a bad option. Options that no case can meet are
// found only by generating.
void check_generator_options(const std::string& family, const nlohmann::json& options);

}  // namespace rrlab
