// Seeded perturbation families of one scenario (a file or catalogue
// scenario): each case is the scenario with its obstacles moved and turned,
// its path run faster or slower, its start moved along the self-motion
// manifold and its path moved, each by an amount drawn from the case's own
// random stream. A case is a whole scenario document (name "<name>-p<index>",
// a "perturbation" object recording what was drawn), so it reproduces from
// its record alone. A draw whose start leaves the joint limits, touches an
// obstacle or touches itself is redrawn. The options, as a sweep entry writes them:
//   {"perturb": SCENARIO, "count": N, "seed": S,
//    "obstacles": {"shift": m | "shift_reach": f, "shift_gap": g, "rotate_deg": deg, "together": bool},
//    "speed": [min, max] | s, "q0_self_motion": rad, "path": {"shift": m | "shift_reach": f, "shift_gap": g}}
// A shift_reach is a fraction of the arm's reach, capped at shift_gap times
// the scene's free gap (PerturbationScale). Meaning of each: docs/generators.md,
// "Perturbation families".
#pragma once

#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

namespace rrlab {

struct Scenario;

// A shift given in metres, or as a fraction of the arm's reach capped at a
// fraction of the scene's free gap (PerturbationScale): the radius it moves by.
struct PerturbationShift {
  double metres = 0;        // "shift"
  double reach = 0;         // "shift_reach": this times the reach (> 0: the metres are not used)
  double gap = 0.5;         // "shift_gap": at most this times the free gap (with shift_reach only)

  bool sized_to_scene() const { return reach > 0; }
};

// What sizes a shift_reach, measured once on the scenario as given (obstacles
// at t = 0, the arm at q0):
//   reach     Model::reach(): the sum of the chain's fixed offsets (for planar
//             and spatial_xz arms the sum of the link lengths), the farthest
//             the hand can be from the first joint
//   free_gap  the least of the start arm's clearance (least link-obstacle
//             distance) and the least positive distance between two obstacles
//             (obstacles that touch or overlap make one body and no gap);
//             +inf without obstacles
struct PerturbationScale {
  double reach = 0;                                          // m
  double free_gap = std::numeric_limits<double>::infinity(); // m
};
PerturbationScale perturbation_scale(const Scenario& sc);

struct PerturbationOptions {
  PerturbationShift obstacle_shift; // each obstacle moved by a vector uniform in the disc (planar robot) or ball of this radius
  double obstacle_rotate_deg = 0;  // each obstacle turned about the vertical through its centre, uniform in ±this
  bool obstacles_together = false; // one shift and turn for the whole scene (about the mean of the obstacles' places)
  double speed_min = 1, speed_max = 1;  // the path's times divided by s, log-uniform in [min, max]
  double q0_self_motion = 0;       // rad: joint-space arc length along the self-motion manifold, uniform in [0, this]
  PerturbationShift path_shift;    // the whole path moved by a vector uniform in the disc (xy task) or ball of this radius

  bool changes_anything() const;
  bool sized_to_scene() const { return obstacle_shift.sized_to_scene() || path_shift.sized_to_scene(); }
};

// The entry's perturbation keys (obstacles, speed, q0_self_motion, path);
// other keys are the caller's ("perturb", "count", "seed"). Throws
// ScenarioError naming the key under `path`.
PerturbationOptions parse_perturbation_options(const nlohmann::json& entry, const std::string& path);

// Case `index` of the family of `base` (a scenario document; `dir` resolves
// its URDF and mesh files as for the file itself) under `seed`. `name` names
// the family (catalogue name or file stem) and seeds its stream with `seed`
// and `index`. Throws ScenarioError when the base does not parse or no draw
// within kCaseAttempts (200) starts inside the limits, clear of obstacles
// and of itself (the error counts each reason and names the keys to reduce).
// `scale` is perturbation_scale() of the base, for callers that make many
// cases of one scenario (a sweep entry measures it once); without it, it is
// measured when the options need it.
nlohmann::json perturb_scenario(const nlohmann::json& base, const std::string& dir, const std::string& name,
                                const PerturbationOptions& options, const PerturbationScale& scale, std::uint64_t seed,
                                int index);
nlohmann::json perturb_scenario(const nlohmann::json& base, const std::string& dir, const std::string& name,
                                const PerturbationOptions& options, std::uint64_t seed, int index);

}  // namespace rrlab
