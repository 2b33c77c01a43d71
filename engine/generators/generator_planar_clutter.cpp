// Family planar_clutter: a planar arm among static obstacles of mixed shapes,
// its hand on the trace of a witness (generator_witness.hpp).
//
// | option        | meaning                                              | default                 | unit     |
// |---------------|------------------------------------------------------|-------------------------|----------|
// | dof           | joints (links) of the arm, [min, max] or a number    | [3, 12]                 | —        |
// | link_length   | each link's length, drawn per link                   | [0.2, 0.6]              | m        |
// | link_radius   | every link's capsule radius                          | 0.02                    | m        |
// | obstacles     | obstacle count (the blocking ones among them)        | [2, 8]                  | —        |
// | obstacle_size | sphere radius / box half-edge / polygon radius       | [0.04, 0.12]            | × reach  |
// | shapes        | shapes drawn from (uniformly)                        | sphere, box, polygon, point | —    |
// | blocking      | obstacles on pinv's arm, each met where no other is  | 2                       | —        |
// | block_pinv    | false: blocking 0                                    | true                    | —        |
// | clearance     | least distance from the witness arm, every step | 0.05                    | m        |
// | waypoints     | waypoints after the start                            | [2, 4]                  | —        |
// | speed         | hand speed the witness is timed by                     | 0.2 × reach per second  | m/s      |
// | dt            | time step                                            | 0.01                    | s        |
// | time_law      | "quintic" (rest to rest) or "linear" (the witness) | quintic                   | —        |
//
// Every obstacle keeps the clearance from the witness arm at every step: the
// task stays feasible. The first `blocking` stand on the arm of the
// minimum-norm solution (generator_blocking.hpp); of the others every other
// one is drawn beside the witness arm, the rest anywhere within reach
// (place_clutter, generator_clutter.hpp).
#include <rrlab/generators/generator_arms.hpp>
#include <rrlab/generators/generator_blocking.hpp>
#include <rrlab/generators/generator_case.hpp>
#include <rrlab/generators/generator_clutter.hpp>
#include <rrlab/generators/generator_path.hpp>

namespace rrlab {

nlohmann::json generate_planar_clutter(GeneratorCase& c) {
  const GeneratorOptions options(c.options, c.family,
                                 {"dof", "link_length", "link_radius", "obstacles", "obstacle_size", "shapes",
                                  "clearance", "blocking", "block_pinv", "waypoints", "speed", "dt", "time_law"});
  const PlanarArmOptions arm_options = read_planar_arm_options(options, false);
  const ClutterOptions clutter = read_clutter_options(options, {2, 8}, {"sphere", "box", "polygon", "point"}, read_blocking(options, c));
  const PathOptions path_options = read_path_options(options);
  if (c.options_only) return nullptr;
  return generate_clutter_case(
      c, clutter, path_options, [&](Rng& r) { return draw_planar_arm(arm_options, r); }, false, TaskSpace::xy);
}

}  // namespace rrlab
