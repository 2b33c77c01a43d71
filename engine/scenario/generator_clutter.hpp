// Static clutter around a generated arm's witness: the obstacles of
// planar_clutter, spatial_clutter and planar_limits.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>

#include "scenario/generator_arms.hpp"
#include "scenario/generator_case.hpp"
#include "scenario/generator_obstacles.hpp"
#include "scenario/generator_witness.hpp"

namespace rrlab {

// Draws the option's obstacle count: every other obstacle (the 1st, 3rd, ...)
// within 0.25 reach of a random point of the hand's trace, where it matters,
// the rest anywhere within reach of the base; each more than the clearance
// from every link of the witness arm at every step. Nullopt when one found no
// place.
std::optional<nlohmann::json> place_clutter(const ClutterOptions& clutter, const WitnessedArm& drawn, bool spatial,
                                            Rng& rng);

// A case of planar_clutter or spatial_clutter: an arm from `draw_arm`, its
// witness, and static clutter clear of the witness, tracked in `space`.
nlohmann::json generate_clutter_case(GeneratorCase& c, const ClutterOptions& clutter, const PathOptions& path_options,
                                     const std::function<GeneratedArm(Rng&)>& draw_arm, bool spatial,
                                     TaskSpace space);

}  // namespace rrlab
