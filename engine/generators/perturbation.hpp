// Seeded perturbation families of one scenario (a file or catalogue
// scenario): each case is the scenario with its obstacles moved and turned,
// its path run faster or slower, its start moved along the self-motion
// manifold and its path moved, each by an amount drawn from the case's own
// random stream. A case is a whole scenario document (name "<name>-p<index>",
// a "perturbation" object recording what was drawn), so it reproduces from
// its record alone. A draw whose start collides or leaves the joint limits
// is redrawn. The options, as a sweep entry writes them:
//   {"perturb": SCENARIO, "count": N, "seed": S,
//    "obstacles": {"shift": m, "rotate_deg": deg, "together": bool}, "speed": [min, max] | s,
//    "q0_self_motion": rad, "path": {"shift": m}}
// Meaning of each: docs/generators.md, "Perturbation families".
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

namespace rrlab {

struct PerturbationOptions {
  double obstacle_shift = 0;       // m: each obstacle moved by a vector uniform in the disc (planar robot) or ball of this radius
  double obstacle_rotate_deg = 0;  // each obstacle turned about the vertical through its centre, uniform in ±this
  bool obstacles_together = false; // one shift and turn for the whole scene (about the mean of the obstacles' places)
  double speed_min = 1, speed_max = 1;  // the path's times divided by s, log-uniform in [min, max]
  double q0_self_motion = 0;       // rad: joint-space arc length along the self-motion manifold, uniform in [0, this]
  double path_shift = 0;           // m: the whole path moved by a vector uniform in the disc (xy task) or ball of this radius

  bool changes_anything() const;
};

// The entry's perturbation keys (obstacles, speed, q0_self_motion, path);
// other keys are the caller's ("perturb", "count", "seed"). Throws
// ScenarioError naming the key under `path`.
PerturbationOptions parse_perturbation_options(const nlohmann::json& entry, const std::string& path);

// Case `index` of the family of `base` (a scenario document; `dir` resolves
// its URDF and mesh files as for the file itself) under `seed`. `name` names
// the family (catalogue name or file stem) and seeds its stream with `seed`
// and `index`. Throws ScenarioError when the base does not parse or no draw
// within 200 starts clear of obstacles and inside the limits.
nlohmann::json perturb_scenario(const nlohmann::json& base, const std::string& dir, const std::string& name,
                                const PerturbationOptions& options, std::uint64_t seed, int index);

}  // namespace rrlab
