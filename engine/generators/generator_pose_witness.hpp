// The witness of a pose-task case: the hand moves on straight lines through
// drawn positions at one fixed orientation (the start configuration's,
// rounded as the task writes it), timed by the time law per segment; the
// joints follow by Newton steps on the full pose at every step, from the
// previous step's configuration, with a null-space pull toward a drawn
// posture (a self-motion of its own, so that the witness is not what the
// minimum-norm solution does). Sampled like every witness (finish_witness),
// with the orientation held to kOrientationTolerance.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include <rrlab/generators/generator_arms.hpp>
#include <rrlab/generators/generator_path.hpp>
#include <rrlab/generators/generator_witness.hpp>
#include <rrlab/util/rng.hpp>

namespace rrlab {

// From q0 (its hand first) through `points`. Nullopt when Newton does not
// hold the pose at some step, a joint leaves the arm's draw box, or a joint
// would exceed kVelocityLimitShare of its velocity limit even at a quarter
// of the drawn speed.
std::optional<GeneratedWitness> build_pose_witness(const GeneratedArm& arm, const Eigen::VectorXd& q0,
                                                   const std::vector<Eigen::Vector3d>& points,
                                                   const PathOptions& options, Rng& rng);

// The draw_witnessed_arm() of pose families: `path` holds q0 and, as its
// points, the witness's hand trace.
std::optional<WitnessedArm> pose_witnessed_arm(GeneratedArm arm, const Eigen::VectorXd& q0,
                                               const std::vector<Eigen::Vector3d>& points,
                                               const PathOptions& options, Rng& rng);

}  // namespace rrlab
