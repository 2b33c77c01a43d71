// Family urdf_tabletop: a shipped URDF arm (iiwa 14, Panda, Gen3) over a
// table with blocks and cylinders on it; the hand keeps one orientation
// (task space "pose") on straight lines between points above the table,
// between and over the objects (generator_pose_witness.hpp).
//
// | option        | meaning                                                      | default            | unit |
// |---------------|--------------------------------------------------------------|--------------------|------|
// | arms          | arms drawn from (uniformly)                                  | iiwa14, panda, gen3 | —   |
// | table_height  | the table top's height above the base                        | [-0.1, 0.2]        | m    |
// | objects       | blocks and cylinders on the table                            | [2, 6]             | —    |
// | object_size   | a block's half width / a cylinder's radius                   | [0.03, 0.07]       | m    |
// | object_height | an object's height                                           | [0.05, 0.3]        | m    |
// | shapes        | shapes drawn from: "box", "cylinder"                         | box, cylinder      | —    |
// | clearance     | least distance of table and objects from the witness arm     | 0.03               | m    |
// | blocking      | balls (among the objects) reaching into the minimum-norm arm (pinv) | 2       | —    |
// | block_pinv    | false: blocking 0                                            | true               | —    |
// | waypoints     | hand points above the table after the start                  | [2, 4]             | —    |
// | speed         | hand speed the witness is timed by                           | 0.2 × reach per s  | m/s  |
// | dt            | time step                                                    | 0.01               | s    |
// | time_law      | "linear" or "quintic" (per segment)                          | quintic            | —    |
//
// The table (0.5 m deep, 0.9 m wide, 4 cm thick) stands 0.45-0.6 m in front
// of the base, turned by up to 45 deg about z. The start is the arm's ready
// posture moved by up to 0.3 rad per joint; its hand orientation is the
// task's. Hand points are 0.1-0.35 m above the table top, 0.1 m apart at
// least. The table, then every object, keeps the clearance from every link of
// the witness arm at every step; every other object stands under a point of
// the hand's trace (the hand passes over it), the others beside one. The
// first `blocking` objects are balls (radius 1-5 cm) reaching into the arm of
// a pinv run of the case without obstacles, each where no other is, clear of
// the witness arm (balls_on_pinv): tracking the path takes a use of the
// redundancy other than minimum norm.
#include <cmath>

#include <rrlab/generators/generator_blocking.hpp>
#include <rrlab/generators/generator_case.hpp>
#include <rrlab/generators/generator_clutter.hpp>
#include <rrlab/generators/generator_furniture.hpp>
#include <rrlab/generators/generator_obstacles.hpp>
#include <rrlab/generators/generator_pose_witness.hpp>
#include <rrlab/generators/generator_urdf_arms.hpp>
#include <rrlab/scenario/scenario.hpp>

namespace rrlab {

namespace {

constexpr double kTableDepth = 0.5, kTableWidth = 0.9, kTableThickness = 0.04;  // m
constexpr double kHandAboveTable[2] = {0.1, 0.35};                     // m over the top
constexpr double kTablePointSpacing = 0.1;                             // m
constexpr Range kBallRadius{0.01, 0.05};                               // m

struct TabletopOptions {
  std::vector<std::string> arms;
  Range height{-0.1, 0.2}, size{0.03, 0.07}, object_height{0.05, 0.3};
  IntRange objects{2, 6};
  std::vector<std::string> shapes;
  double clearance = 0.03;
  IntRange blocking{0, 0};  // balls on pinv's arm (among the objects)
  PathOptions path;
};

// Hand points above the table top at `top` (frame coordinates), spaced.
std::optional<std::vector<Eigen::Vector3d>> draw_table_points(const FloorFrame& table, double top, int count, Rng& rng) {
  std::vector<Eigen::Vector3d> points;
  for (int tries = 0; tries < 100 && int(points.size()) < count; ++tries) {
    // one draw per statement: the order of a call's arguments is up to the compiler
    const double along = rng.uniform(-0.4, 0.4) * kTableDepth;
    const double across = rng.uniform(-0.4, 0.4) * kTableWidth;
    const double above = rng.uniform(kHandAboveTable[0], kHandAboveTable[1]);
    const Eigen::Vector3d local(along, across, top + above);
    const Eigen::Vector3d p = table.world(local);
    if (!points.empty() && (p - points.back()).norm() < kTablePointSpacing) continue;
    points.push_back({rounded(p.x(), 1e-4), rounded(p.y(), 1e-4), rounded(p.z(), 1e-4)});
  }
  if (int(points.size()) < count) return std::nullopt;
  return points;
}

}  // namespace

nlohmann::json generate_urdf_tabletop(GeneratorCase& c) {
  const GeneratorOptions options(c.options, c.family,
                                 {"arms", "table_height", "objects", "object_size", "object_height", "shapes",
                                  "clearance", "blocking", "block_pinv", "waypoints", "speed", "dt", "time_law"});
  TabletopOptions o;
  o.arms = read_urdf_arms(options);
  o.height = options.range("table_height", o.height, {-0.5, 1.0});
  o.objects = options.int_range("objects", o.objects, {0, 32});
  o.size = options.range("object_size", o.size, {0.005, 0.3});
  o.object_height = options.range("object_height", o.object_height, {0.005, 1.0});
  o.shapes = options.subset("shapes", {"box", "cylinder"}, {"box", "cylinder"});
  o.clearance = options.number("clearance", o.clearance, {0.0, 0.5});
  o.blocking = read_blocking(options, c);
  if (o.objects.min < o.blocking.max)
    throw ScenarioError("options.objects", "must be at least " + std::to_string(o.blocking.max) + " with blocking " +
                                               std::to_string(o.blocking.max) +
                                               " (the balls are among them; set block_pinv false for none)");
  o.path = read_path_options(options);
  if (c.options_only) return nullptr;

  Rng& rng = c.rng;
  for (int attempt = 0; attempt < kCaseAttempts; ++attempt) {
    GeneratedArm arm = draw_urdf_arm(o.arms, rng);
    const FloorFrame table{{0, 0, 0}, rng.uniform(-M_PI / 4, M_PI / 4)};
    const double distance = rng.uniform(0.45, 0.6), top = rounded(o.height.draw(rng), 1e-4);
    const FloorFrame frame{table.world({distance, 0, 0}), table.yaw};  // the table's centre, floor level
    const Eigen::VectorXd q0 = draw_ready_configuration(arm, kReadySpread, rng);
    const std::optional<std::vector<Eigen::Vector3d>> points = draw_table_points(frame, top, o.path.waypoints.draw(rng), rng);
    if (!points) continue;
    std::optional<WitnessedArm> drawn = pose_witnessed_arm(std::move(arm), q0, *points, o.path, rng);
    if (!drawn) continue;
    nlohmann::json obstacles = nlohmann::json::array();
    obstacles.push_back(frame_box("table", frame, {0, 0, top - kTableThickness / 2}, {kTableDepth, kTableWidth, kTableThickness}));
    const KeepOut keep_out{&drawn->sweep, o.clearance};
    if (!keeps_out(obstacles[0], keep_out)) continue;
    const int blocking = o.blocking.draw(rng);
    int balls = 0;
    if (blocking > 0) {  // balls hanging where the minimum-norm arm passes
      const std::optional<ArmSweep> pinv = minimum_norm_sweep(c, *drawn, TaskSpace::pose);
      if (!pinv) continue;
      PinvBlockers blockers(*pinv, drawn->sweep, o.clearance);
      const std::optional<nlohmann::json> on_pinv = balls_on_pinv(blocking, blockers, kBallRadius, rng);
      if (!on_pinv) continue;
      for (const nlohmann::json& ball : *on_pinv) obstacles.push_back(ball);
      balls = int(on_pinv->size());
    }
    const std::vector<Eigen::Vector3d>& trace = drawn->witness.hand;
    const auto draw = [&](int k, Rng& r) -> std::optional<nlohmann::json> {
      const std::string& shape = o.shapes[r.below(o.shapes.size())];
      const double size = rounded(o.size.draw(r), 1e-4);
      double height = rounded(o.object_height.draw(r), 1e-4);
      const Eigen::Vector3d hand = frame.local(trace[r.below(trace.size())]);
      Eigen::Vector3d at(hand.x(), hand.y(), top);
      if (k % 2 == 0) {  // under the hand: low enough for it to pass over
        height = std::min(height, hand.z() - top - drawn->arm.link_radius - o.clearance - 0.01);
        if (height < 0.01) return std::nullopt;
      } else {  // beside the hand's trace
        const double a = r.uniform(0, 2 * M_PI);
        const double extra_clearance = r.uniform(), extra = r.uniform();
        const double out = size + drawn->arm.link_radius + o.clearance * (1 + extra_clearance) + 0.05 * extra;
        at += out * Eigen::Vector3d(std::cos(a), std::sin(a), 0);
      }
      if (std::abs(at.x()) > kTableDepth / 2 - size || std::abs(at.y()) > kTableWidth / 2 - size) return std::nullopt;
      const std::string id = shape + std::to_string(k + 1);
      if (shape == "box") {
        const double aspect = r.uniform(0.6, 1.4), turn = r.uniform(-M_PI / 4, M_PI / 4);
        return frame_box(id, frame, {at.x(), at.y(), top + height / 2}, {2 * size, 2 * size * aspect, height}, turn);
      }
      return frame_cylinder(id, frame, at, size, height);
    };
    const int count = o.objects.draw(rng) - balls;
    const std::optional<nlohmann::json> objects = place_obstacles(std::max(0, count), keep_out, draw, rng);
    if (!objects) continue;
    for (const nlohmann::json& object : *objects) obstacles.push_back(object);
    const std::string description =
        case_title(c) + ": " + drawn->arm.summary + " over a table (top " + fixed_digits(top, 3) + " m above the base) with " +
std::to_string(objects->size()) + " objects" + blocking_summary(balls, "ball") + ", each, and the table, more than " + fixed_digits(o.clearance, 3) +
        " m from every link of the witness arm at every step; the hand keeps its start orientation on straight lines through " +
        std::to_string(points->size()) + " points above the table, " + fixed_digits(drawn->witness.length, 3) + " m at " +
        fixed_digits(drawn->witness.speed, 3) + " m/s (" + fixed_digits(drawn->witness.duration, 2) + " s, " +
        drawn->witness.time_law + " time law per segment).";
    return witnessed_document(c, description, *drawn, obstacles, TaskSpace::pose, o.clearance);
  }
  no_case_found(c, "options.table_height, options.objects, options.object_height, options.clearance or options.blocking");
}

}  // namespace rrlab
