// Steady-state steps must not touch the heap: a counting global operator new
// watches a window of steps after warm-up.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "engine/sim_helpers.hpp"
#include "engine/test_models.hpp"

namespace {
std::atomic<long> g_allocations{0};
std::atomic<bool> g_counting{false};
}  // namespace

void* operator new(std::size_t size) {
  if (g_counting.load(std::memory_order_relaxed)) g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace rrlab {
namespace {

long allocations_in_steps(Simulator& sim, int steps) {
  for (int i = 0; i < 5; ++i) sim.step();  // warm-up
  g_allocations = 0;
  g_counting = true;
  for (int i = 0; i < steps; ++i) sim.step();
  g_counting = false;
  return g_allocations.load();
}

nlohmann::json dh7_scenario(const std::string& method) {
  nlohmann::json links = nlohmann::json::array();
  for (const DhLinkSpec& l : test::iiwa_dh())
    links.push_back({{"a", l.a}, {"alpha", l.alpha}, {"d", l.d}, {"radius", l.radius}});
  return {{"dt", 0.005},
          {"duration", 2.0},
          {"robot", {{"kind", "dh"}, {"links", links}, {"q0", {0, 0.7, 0, -1.2, 0, 1.0, 0}}}},
          {"task", {{"space", "pose"},
                    {"trajectory", {{"type", "circle"}, {"center", {0.5, -0.12, 0.55}}, {"radius", 0.12},
                                    {"normal", {1, 0, 0}}}}}},
          {"method", {{"name", method}}}};
}

class NoAllocation : public ::testing::TestWithParam<std::string> {};

TEST_P(NoAllocation, SteadyStateStepWithoutObstacles) {
  Simulator sim(parse_scenario(dh7_scenario(GetParam())));
  EXPECT_EQ(allocations_in_steps(sim, 100), 0) << GetParam();
}

TEST_P(NoAllocation, SteadyStateStepAmongObstacles) {
  nlohmann::json doc = dh7_scenario(GetParam());
  doc["obstacles"] = {{{"shape", "sphere"}, {"center", {0.4, 0.3, 0.6}}, {"radius", 0.1}},
                      {{"shape", "box"}, {"center", {0.6, 0.0, 0.1}}, {"size", {0.4, 0.6, 0.2}}},
                      {{"shape", "point"}, {"position", {0.3, -0.3, 0.4}}, {"velocity", {0.01, 0, 0}}},
                      {{"shape", "wall"}, {"point", {0, 0, -0.1}}, {"normal", {0, 0, 1}}},
                      {{"shape", "polygon"}, {"points", {{0.8, 0.4}, {1.0, 0.4}, {0.9, 0.6}}}, {"z", {0, 0.3}}}};
  Simulator sim(parse_scenario(doc));
  EXPECT_EQ(allocations_in_steps(sim, 100), 0) << GetParam();
}

INSTANTIATE_TEST_SUITE_P(Baselines, NoAllocation,
                         ::testing::Values("pinv", "dls", "gpm", "task_priority", "sr_task_priority",
                                           "closest_point", "posture_generation", "ccp_voronoi",
                                           "multi_preview", "qp_constraints", "direct_search", "qp_ik", "hqp",
                                           "diffik"));

// A mesh obstacle (scenario 43's hoop: capsule links against its BVH, by
// collision_world's own descent) costs no allocation either. (FCL's
// fcl::distance on a capsule and a BVHModel would: 2 per call, bounding the
// capsule; it serves only as compute_with_fcl's reference.)
TEST_P(NoAllocation, SteadyStateStepWithAMeshObstacle) {
  Scenario sc = load_scenario_file(test::source_path("scenarios/43_urdf_iiwa14_mesh_obstacle.json"));
  sc.method.name = GetParam();
  sc.method.params.clear();
  Simulator sim(sc);
  EXPECT_EQ(allocations_in_steps(sim, 100), 0) << GetParam();
}

// Variants of the paper methods beyond their defaults.
TEST(NoAllocation, CcpVoronoiLagrangianAndHybrid) {
  nlohmann::json doc = dh7_scenario("ccp_voronoi");
  doc["obstacles"] = {{{"shape", "box"}, {"center", {0.6, 0.0, 0.1}}, {"size", {0.4, 0.6, 0.2}}},
                      {{"shape", "sphere"}, {"center", {0.4, 0.3, 0.6}}, {"radius", 0.1}}};
  for (const char* params : {R"({"integrator": "lagrangian", "ccp2_link": 5})", R"({"mode": "hybrid", "ccp2_link": 5})"}) {
    doc["method"]["params"] = nlohmann::json::parse(params);
    Simulator sim(parse_scenario(doc));
    EXPECT_EQ(allocations_in_steps(sim, 50), 0) << params;
  }
}


// multi_preview's path planning (previews = 0) plans on its first step, then only follows the plan
TEST(NoAllocation, MultiPreviewPathPlanningAfterThePlan) {
  nlohmann::json doc = dh7_scenario("multi_preview");
  doc["method"]["params"] = {{"previews", 0}, {"plan_interval", 0.25}, {"warmup_generations", 5}};
  Simulator sim(parse_scenario(doc));
  EXPECT_EQ(allocations_in_steps(sim, 100), 0);
}

TEST(NoAllocation, DirectSearchWithBlockSwitch) {
  Simulator sim(load_scenario_file(test::source_path("scenarios/22_kapoor_square_circle.json")));
  sim.set_param("block_switch", 1.0);  // every step searches the largest-determinant block
  EXPECT_EQ(allocations_in_steps(sim, 50), 0);
}

// The GA's closed-form planar arm and its 2D obstacle distances (Zhang's
// object, plus a moving ball and a box), and direct_search on the same arm
TEST(NoAllocation, PlanarMultiPreviewAndDirectSearch) {
  Scenario sc = load_scenario_file(test::source_path("scenarios/31_zhang_multi_preview.json"));
  Obstacle box;
  box.id = "box";
  box.shape = ShapeKind::box;
  box.size = Eigen::Vector3d(0.2, 0.3, 1.0);
  box.position = box.position0 = Eigen::Vector3d(-0.5, -1.0, 0.0);
  sc.scene.obstacles.push_back(test::moving_ball("ball", {-1.0, 1.0, 0.0}, 0.1, {0.01, 0, 0}));
  sc.scene.obstacles.push_back(box);
  Simulator preview(sc);
  EXPECT_EQ(allocations_in_steps(preview, 50), 0);
  Simulator search(sc, "direct_search");
  EXPECT_EQ(allocations_in_steps(search, 50), 0);
}

TEST(NoAllocation, CounterSeesAllocations) {
  g_allocations = 0;
  g_counting = true;
  auto* v = new std::vector<double>(100);
  g_counting = false;
  delete v;
  EXPECT_GE(g_allocations.load(), 1);
}

}  // namespace
}  // namespace rrlab
