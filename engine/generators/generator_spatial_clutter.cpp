// Family spatial_clutter: a 7-DOF DH arm after the KUKA LBR iiwa among
// spheres and boxes, its hand on the 3D trace (task space "xyz") of a
// witness (generator_witness.hpp).
//
// | option        | meaning                                                 | default                 | unit    |
// |---------------|---------------------------------------------------------|-------------------------|---------|
// | length_scale  | factor on each of the iiwa's d (0.36, 0.42, 0.40, 0.126 m), drawn per link | [0.8, 1.2] | — |
// | a_offset      | each link's a (the iiwa has 0)                          | [-0.05, 0.05]           | m       |
// | link_radius   | every link's capsule radius                             | 0.05                    | m       |
// | obstacles     | obstacle count (the blocking ones among them)           | [2, 8]                  | —       |
// | obstacle_size | sphere radius / box half-edge                           | [0.04, 0.12]            | × reach |
// | shapes        | shapes drawn from (uniformly)                           | sphere, box             | —       |
// | clearance     | least distance from the witness arm, every step    | 0.05                    | m       |
// | blocking      | obstacles on pinv's arm, each met where no other is     | 2                       | —       |
// | block_pinv    | false: blocking 0                                       | true                    | —       |
// | waypoints     | waypoints after the start                               | [2, 4]                  | —       |
// | speed         | hand speed the witness is timed by                        | 0.2 × reach per second  | m/s     |
// | dt            | time step                                               | 0.01                    | s       |
// | time_law      | "linear" (constant speed) or "quintic" (per segment)    | linear                  | —       |
//
// Each alpha is +90 or -90 deg (drawn; the last 0), joint limits are the
// iiwa's (+-170, 120, 170, 120, 170, 120, 175 deg), configurations are drawn
// within 0.9 of them. Obstacles keep the clearance from the witness arm at
// every step; the first `blocking` stand on the arm of the minimum-norm
// solution, of the others every other one beside the witness arm, the rest
// anywhere within reach (place_clutter).
#include <rrlab/generators/generator_arms.hpp>
#include <rrlab/generators/generator_blocking.hpp>
#include <rrlab/generators/generator_case.hpp>
#include <rrlab/generators/generator_clutter.hpp>
#include <rrlab/generators/generator_path.hpp>

namespace rrlab {

nlohmann::json generate_spatial_clutter(GeneratorCase& c) {
  const GeneratorOptions options(c.options, c.family,
                                 {"length_scale", "a_offset", "link_radius", "obstacles", "obstacle_size", "shapes",
                                  "clearance", "blocking", "block_pinv", "waypoints", "speed", "dt", "time_law"});
  const DhArmOptions arm_options = read_dh_arm_options(options);
  const ClutterOptions clutter = read_clutter_options(options, {2, 8}, {"sphere", "box"}, read_blocking(options, c));
  const PathOptions path_options = read_path_options(options);
  if (c.options_only) return nullptr;
  return generate_clutter_case(
      c, clutter, path_options, [&](Rng& r) { return draw_dh7_arm(arm_options, r); }, true, TaskSpace::xyz);
}

}  // namespace rrlab
