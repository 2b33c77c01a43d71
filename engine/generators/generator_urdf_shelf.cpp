// Family urdf_shelf: a shipped URDF arm (iiwa 14, Panda, Gen3) reaching into
// a compartment of a shelf and out again; the hand keeps one orientation
// (task space "pose") on straight lines (generator_pose_witness.hpp).
//
// | option          | meaning                                                   | default            | unit |
// |-----------------|-----------------------------------------------------------|--------------------|------|
// | arms            | arms drawn from (uniformly)                               | iiwa14, panda, gen3 | —   |
// | reach_in        | how far the hand goes behind the shelf's front            | [0.08, 0.2]        | m    |
// | opening_height  | height of the compartment's opening above the base        | [0.1, 0.7]         | m    |
// | gap             | the compartment's play (at least 5 mm): each board's extra distance from the witness arm, beyond the clearance | [0.01, 0.06] | m |
// | clearance       | least distance of every board from the witness arm        | 0.03               | m    |
// | blocking        | balls (radius 1-5 cm) reaching into the minimum-norm arm (pinv) | 2            | —    |
// | block_pinv      | false: blocking 0                                         | true               | —    |
// | speed           | hand speed the witness is timed by                        | 0.2 × reach per s  | m/s  |
// | dt              | time step                                                 | 0.01               | s    |
// | time_law        | "linear" or "quintic" (per segment)                       | quintic            | —    |
//
// The shelf's front stands 0.45-0.6 m from the base, turned by up to 45 deg
// about z. The start is the arm's ready posture moved by up to 0.3 rad per
// joint (its hand orientation is the task's); the hand goes to a point 0.1 m
// in front of the opening, in to `reach_in` behind the front, back out, and
// to a last point drawn in front of the shelf. The compartment is built
// around the witness: its floor, ceiling and sides are the clearance plus
// the gap from the part of the witness arm inside the shelf at any step; a
// board above and below it make the next compartments, the back closes it.
// Every board keeps the clearance from every link at every step. `blocking`
// balls reach into the arm of a pinv run of the case without obstacles, each
// where no other is, clear of the witness arm (balls_on_pinv; without them
// pinv's arm, whose hand and forearm inside the shelf move as the witness's,
// hit no board in 30 of 30 cases): the witness's own self-motion is needed.
#include <algorithm>
#include <cmath>

#include <rrlab/generators/generator_blocking.hpp>
#include <rrlab/generators/generator_case.hpp>
#include <rrlab/generators/generator_clutter.hpp>
#include <rrlab/generators/generator_furniture.hpp>
#include <rrlab/generators/generator_obstacles.hpp>
#include <rrlab/generators/generator_pose_witness.hpp>
#include <rrlab/generators/generator_urdf_arms.hpp>
#include <rrlab/generators/generator_witness.hpp>

namespace rrlab {

namespace {

constexpr double kShelfBoard = 0.02;       // m thick
constexpr double kShelfApproach = 0.1;     // m in front of the opening
constexpr Range kShelfBall{0.01, 0.05};    // m: radius of a ball on pinv's arm

constexpr int kShelfCapsulePoints = 8;  // points per capsule when bounding the arm inside the shelf (every board is then checked exactly)

struct ShelfExtent {
  double y_min = INFINITY, y_max = -INFINITY, z_min = INFINITY, z_max = -INFINITY, x_max = -INFINITY;
  bool any = false;
};

// The box (shelf frame) the witness arm occupies behind the plane x = front, radii included.
ShelfExtent shelf_inside_extent(const ArmSweep& sweep, const FloorFrame& shelf, double front) {
  ShelfExtent e;
  for (const CapsuleSegment& c : sweep.capsules)
    for (int k = 0; k <= kShelfCapsulePoints; ++k) {
      const Eigen::Vector3d p = shelf.local(c.a + (double(k) / kShelfCapsulePoints) * (c.b - c.a));
      if (p.x() + c.radius < front) continue;
      e.any = true;
      e.y_min = std::min(e.y_min, p.y() - c.radius), e.y_max = std::max(e.y_max, p.y() + c.radius);
      e.z_min = std::min(e.z_min, p.z() - c.radius), e.z_max = std::max(e.z_max, p.z() + c.radius);
      e.x_max = std::max(e.x_max, p.x() + c.radius);
    }
  return e;
}

}  // namespace

nlohmann::json generate_urdf_shelf(GeneratorCase& c) {
  const GeneratorOptions options(c.options, c.family,
                                 {"arms", "reach_in", "opening_height", "gap", "clearance", "blocking", "block_pinv", "speed", "dt",
                                  "time_law"});
  const std::vector<std::string> arms = read_urdf_arms(options);
  const Range reach_in = options.range("reach_in", {0.08, 0.2}, {0.0, 1.0});
  const Range opening = options.range("opening_height", {0.1, 0.7}, {-0.5, 1.5});
  const Range gap = options.range("gap", {0.01, 0.06}, {0.005, 0.5});
  const double clearance = options.number("clearance", 0.03, {0.0, 0.5});
  const IntRange blocking = read_blocking(options, c);
  const PathOptions path = read_path_options(options);
  if (c.options_only) return nullptr;

  Rng& rng = c.rng;
  for (int attempt = 0; attempt < kCaseAttempts; ++attempt) {
    GeneratedArm arm = draw_urdf_arm(arms, rng);
    const double yaw = rng.uniform(-M_PI / 4, M_PI / 4), front = rng.uniform(0.45, 0.6);
    const FloorFrame shelf{{0, 0, 0}, yaw};
    const double y = rng.uniform(-0.15, 0.15), z = opening.draw(rng), depth = reach_in.draw(rng);
    const auto at = [&](double x, double yy, double zz) {
      const Eigen::Vector3d p = shelf.world({x, yy, zz});
      return Eigen::Vector3d(rounded(p.x(), 1e-4), rounded(p.y(), 1e-4), rounded(p.z(), 1e-4));
    };
    // one draw per statement: the order of a call's arguments is up to the compiler
    const double last_back = rng.uniform(0.0, 0.15), last_side = rng.uniform(-0.2, 0.2), last_up = rng.uniform(-0.15, 0.15);
    const std::vector<Eigen::Vector3d> points = {
        at(front - kShelfApproach, y, z), at(front + depth, y, z), at(front - kShelfApproach, y, z),
        at(front - kShelfApproach - last_back, y + last_side, z + last_up)};
    const Eigen::VectorXd q0 = draw_ready_configuration(arm, kReadySpread, rng);
    std::optional<WitnessedArm> drawn = pose_witnessed_arm(std::move(arm), q0, points, path, rng);
    if (!drawn) continue;
    const ShelfExtent e = shelf_inside_extent(drawn->sweep, shelf, front - clearance);
    if (!e.any) continue;
    const double margin = clearance + gap.draw(rng);
    const double floor_top = e.z_min - margin, ceiling = e.z_max + margin;
    const double left = e.y_max + margin, right = e.y_min - margin;
    const double back = std::max(e.x_max + margin, front + depth + 0.1);
    const double above = rng.uniform(0.2, 0.35), below = rng.uniform(0.2, 0.35);
    const double top = ceiling + kShelfBoard + above, bottom = floor_top - kShelfBoard - below;
    const double length = back - front, mid = 0.5 * (front + back);
    const double width = left - right + 2 * kShelfBoard, centre_y = 0.5 * (left + right);
    const double height = top + kShelfBoard - (bottom - kShelfBoard);
    nlohmann::json boards = nlohmann::json::array();
    const auto board = [&](const std::string& id, const Eigen::Vector3d& centre, const Eigen::Vector3d& size) {
      boards.push_back(frame_box(id, shelf, centre, size));
    };
    board("floor", {mid, centre_y, floor_top - kShelfBoard / 2}, {length, width, kShelfBoard});
    board("ceiling", {mid, centre_y, ceiling + kShelfBoard / 2}, {length, width, kShelfBoard});
    board("top", {mid, centre_y, top + kShelfBoard / 2}, {length, width, kShelfBoard});
    board("bottom", {mid, centre_y, bottom - kShelfBoard / 2}, {length, width, kShelfBoard});
    board("left", {mid, left + kShelfBoard / 2, 0.5 * (top + bottom)}, {length, kShelfBoard, height});
    board("right", {mid, right - kShelfBoard / 2, 0.5 * (top + bottom)}, {length, kShelfBoard, height});
    board("back", {back + kShelfBoard / 2, centre_y, 0.5 * (top + bottom)}, {kShelfBoard, width, height});
    const KeepOut keep_out{&drawn->sweep, clearance};
    if (!std::all_of(boards.begin(), boards.end(), [&](const nlohmann::json& b) { return keeps_out(b, keep_out); }))
      continue;
    const int balls = blocking.draw(rng);
    if (balls > 0) {  // balls where the minimum-norm arm passes, clear of the witness arm
      const std::optional<ArmSweep> pinv = minimum_norm_sweep(c, *drawn, TaskSpace::pose);
      if (!pinv) continue;
      PinvBlockers blockers(*pinv, drawn->sweep, clearance);
      const std::optional<nlohmann::json> on_pinv = balls_on_pinv(balls, blockers, kShelfBall, rng);
      if (!on_pinv) continue;
      for (const nlohmann::json& ball : *on_pinv) boards.push_back(ball);
    }
    const std::string description =
        case_title(c) + ": " + drawn->arm.summary + " reaching " + fixed_digits(depth, 3) +
        " m into a shelf compartment (" + fixed_digits(ceiling - floor_top, 3) + " m high, " + fixed_digits(left - right, 3) +
        " m wide, its opening " + fixed_digits(front, 3) + " m from the base) and out again; every board more than " +
        fixed_digits(clearance, 3) + " m from every link of the witness arm at every step" +
        blocking_summary(balls, "ball") +
        "; the hand keeps its start orientation on straight lines, " + fixed_digits(drawn->witness.length, 3) + " m at " +
        fixed_digits(drawn->witness.speed, 3) + " m/s (" + fixed_digits(drawn->witness.duration, 2) + " s, " +
        drawn->witness.time_law + " time law per segment).";
    return witnessed_document(c, description, *drawn, boards, TaskSpace::pose, clearance);
  }
  no_case_found(c, "options.reach_in, options.opening_height, options.gap, options.clearance or options.blocking");
}

}  // namespace rrlab
