// Static clutter around a generated arm's witness: the obstacles of
// planar_clutter, spatial_clutter and planar_limits.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>

#include <rrlab/generators/generator_arms.hpp>
#include <rrlab/generators/generator_blocking.hpp>
#include <rrlab/generators/generator_case.hpp>
#include <rrlab/generators/generator_obstacles.hpp>
#include <rrlab/generators/generator_witness.hpp>

namespace rrlab {

// Draws the option's obstacle count: with `blockers`, the first
// clutter.blocking of them on the axis of pinv's arm at some step, each where
// no other is met (place_blockers); then every other obstacle beside the
// witness arm (out from one of its links at some step by the link's radius,
// the obstacle's size, 1-2 clearances and up to 0.05 reach), the rest
// anywhere within reach of the base; each more than the clearance from every
// link of the witness arm at every step. Nullopt when one found no place.
std::optional<nlohmann::json> place_clutter(const ClutterOptions& clutter, const WitnessedArm& drawn, bool spatial,
                                            Rng& rng, PinvBlockers* blockers = nullptr);

// A case of planar_clutter or spatial_clutter: an arm from `draw_arm`, its
// witness, and static clutter clear of the witness, tracked in `space`.
nlohmann::json generate_clutter_case(GeneratorCase& c, const ClutterOptions& clutter, const PathOptions& path_options,
                                     const std::function<GeneratedArm(Rng&)>& draw_arm, bool spatial,
                                     TaskSpace space);

// For descriptions: ", the first 2 obstacles meeting the arm of the
// minimum-norm solution (pinv) at some step, each where no other does"
// (lead "the first ", noun "obstacle"); empty for none.
std::string blocking_summary(int blocking, const std::string& noun, const std::string& lead = "");

}  // namespace rrlab
