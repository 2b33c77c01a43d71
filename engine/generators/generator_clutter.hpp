// Static clutter around a generated arm's witness: the obstacles of
// planar_clutter, spatial_clutter and planar_limits.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>

#include <rrlab/generators/generator_arms.hpp>
#include <rrlab/generators/generator_case.hpp>
#include <rrlab/generators/generator_obstacles.hpp>
#include <rrlab/generators/generator_witness.hpp>

namespace rrlab {

// The arm of the minimum-norm solution (a pinv run of the case without
// obstacles) at every step; nullopt when pinv's output was not finite.
std::optional<ArmSweep> minimum_norm_sweep(const GeneratorCase& c, const WitnessedArm& drawn, TaskSpace space);

// The capsules of `pinv` (indices, ascending) where its arm strays farthest
// from the witness arm at the same step (link midpoints): the tenth of them
// where an obstacle on pinv's arm can stand clear of the witness.
std::vector<size_t> straying_capsules(const ArmSweep& pinv, const ArmSweep& witness);

// A ball centred on the axis of one of pinv's straying capsules (so that
// pinv's arm, which ignores obstacles, runs into it), as large as `radius`
// allows while it keeps `clearance` from the witness arm at every step: the
// best of `candidates` points drawn on those capsules. Nullopt when none
// leaves a radius of at least radius.min.
std::optional<nlohmann::json> ball_on_pinv(const ArmSweep& pinv, const ArmSweep& witness, double clearance, Range radius,
                                           Rng& rng, int candidates = 24);

// Draws the option's obstacle count: with `blocking`, the first on the axis
// of one of its links at some step (so that arm runs into it); then every
// other obstacle beside the witness arm (out from one of its links at some
// step by the link's radius, the obstacle's size, 1-2 clearances and up to
// 0.05 reach), the rest anywhere within reach of the base; each more than the
// clearance from every link of the witness arm at every step. Nullopt when
// one found no place.
std::optional<nlohmann::json> place_clutter(const ClutterOptions& clutter, const WitnessedArm& drawn, bool spatial,
                                            Rng& rng, const ArmSweep* blocking = nullptr);

// A case of planar_clutter or spatial_clutter: an arm from `draw_arm`, its
// witness, and static clutter clear of the witness, tracked in `space`.
nlohmann::json generate_clutter_case(GeneratorCase& c, const ClutterOptions& clutter, const PathOptions& path_options,
                                     const std::function<GeneratedArm(Rng&)>& draw_arm, bool spatial,
                                     TaskSpace space);

}  // namespace rrlab
