// The distance table and its driver: every link against every obstacle,
// each pair by the function the dispatch table (pair_table.cpp) holds for its
// backend, link shape and obstacle shape.
#include <rrlab/collision/collision_world.hpp>

#include <cmath>
#include <memory>
#include <utility>

#include <rrlab/collision/fcl_pairs.hpp>
#include <rrlab/collision/mesh_distance.hpp>
#include <rrlab/collision/obstacle_geometry.hpp>
#include <rrlab/collision/pair_table.hpp>
#include <rrlab/collision/segment_geometry.hpp>

namespace rrlab {

using collision::kInfinity;

namespace {

void track_minimum(DistanceTable& table, int link, int obstacle) {
  const double distance = table.at(link, obstacle).distance;
  if (distance < table.min_distance) {
    table.min_distance = distance;
    table.min_link = link;
    table.min_obstacle = obstacle;
  }
}

}  // namespace

// --- DistanceTable -----------------------------------------------------------------

void DistanceTable::resize(int link_count, int obstacle_count) {
  links = link_count;
  obstacles = obstacle_count;
  pairs.resize(static_cast<size_t>(link_count) * static_cast<size_t>(obstacle_count));
  min_distance = kInfinity;
  min_link = min_obstacle = -1;
}

int DistanceTable::nearest_obstacle(int link) const {
  int nearest = -1;
  double nearest_distance = kInfinity;
  for (int o = 0; o < obstacles; ++o) {
    if (nearest < 0 || at(link, o).distance < nearest_distance) {
      nearest = o;
      nearest_distance = at(link, o).distance;
    }
  }
  return nearest;
}

// --- CollisionWorld ------------------------------------------------------------------

struct CollisionWorld::Impl {
  std::vector<double> link_radii;
  // mesh links: a BVH per link (null for capsules), posed by joint_frames[last_joint]
  std::vector<std::shared_ptr<collision::MeshBvh>> link_bvh;
  std::vector<std::shared_ptr<const TriangleMesh>> link_mesh;
  std::vector<int> last_joint;
  std::vector<collision::ObstacleGeometry> obstacles;
  // FCL's shapes: capsules for the reference backend, obstacles for it and for mesh links
  std::vector<std::shared_ptr<collision::FclCapsule>> fcl_links;
  std::vector<std::shared_ptr<collision::FclObstacle>> fcl_obstacles;

  void reshape(const Scene& scene) {
    std::vector<collision::ObstacleGeometry> previous = std::move(obstacles);
    obstacles.clear();
    fcl_obstacles.clear();
    for (const Obstacle& o : scene.obstacles) {
      obstacles.push_back(collision::build_geometry(o, previous));  // a mesh's tree is reused from `previous`
      fcl_obstacles.push_back(collision::build_fcl(o, obstacles.back()));
    }
  }

  void read_poses(const Scene& scene) {
    for (size_t i = 0; i < obstacles.size(); ++i) {
      obstacles[i].rotation = scene.obstacles[i].rotation;
      obstacles[i].position = scene.obstacles[i].position;
    }
  }

  // Link l at the kinematics' frames, as the pair functions take it.
  collision::PairLink pair_link(const KinematicsData& kin, int l, DistanceBackend backend) {
    collision::PairLink link;
    if (link_bvh[size_t(l)]) {
      link.mesh = link_mesh[size_t(l)].get();
      link.bvh = link_bvh[size_t(l)].get();
      link.pose = &kin.joint_frames[size_t(last_joint[size_t(l)])];
      return link;
    }
    link.start = kin.link_start.col(l);
    link.end = kin.link_end.col(l);
    link.radius = link_radii[size_t(l)];
    if (backend == DistanceBackend::fcl) {
      collision::pose_fcl_capsule(*fcl_links[size_t(l)], link.start, link.end, link.radius);
      link.fcl = fcl_links[size_t(l)].get();
    }
    return link;
  }
};

CollisionWorld::CollisionWorld(const Model& model, const Scene& scene)
    : impl_(std::make_unique<Impl>()) {
  for (const Link& link : model.links) {
    impl_->link_radii.push_back(link.radius);
    impl_->link_mesh.push_back(link.mesh);
    impl_->link_bvh.push_back(link.mesh ? collision::make_bvh(*link.mesh) : nullptr);
    impl_->last_joint.push_back(link.last_joint);
    impl_->fcl_links.push_back(collision::make_fcl_capsule(link.radius));
  }
  sync(scene, true);
}

CollisionWorld::~CollisionWorld() = default;

void CollisionWorld::sync(const Scene& scene, bool reshape) {
  // a changed obstacle count means new geometry, whatever the caller said
  if (reshape || scene.obstacles.size() != impl_->obstacles.size()) impl_->reshape(scene);
  impl_->read_poses(scene);
}

void CollisionWorld::compute(const KinematicsData& kin, DistanceTable& out, DistanceBackend backend) {
  compute_pairs(kin, out, backend, kInfinity);
}

void CollisionWorld::compute_near(const KinematicsData& kin, DistanceTable& out, double cutoff) {
  compute_pairs(kin, out, DistanceBackend::analytic, cutoff);
}

void CollisionWorld::compute_pairs(const KinematicsData& kin, DistanceTable& out, DistanceBackend backend,
                                   double cutoff) {
  const int link_count = static_cast<int>(impl_->link_radii.size());
  const int obstacle_count = static_cast<int>(impl_->obstacles.size());
  out.resize(link_count, obstacle_count);
  for (int l = 0; l < link_count; ++l) {
    const collision::LinkShape shape =
        impl_->link_bvh[size_t(l)] ? collision::LinkShape::mesh : collision::LinkShape::capsule;
    const collision::PairLink link = impl_->pair_link(kin, l, backend);
    for (int o = 0; o < obstacle_count; ++o) {
      const collision::ObstacleGeometry& g = impl_->obstacles[size_t(o)];
      if (cutoff < kInfinity && shape == collision::LinkShape::capsule && !g.parts.empty()) {
        const double bound = collision::segment_polytopes_bound(g, link.start, link.end) - link.radius;
        if (bound > cutoff + collision::kBoundMargin) {
          LinkObstacleDistance& far = out.at(l, o);
          far.distance = bound;
          far.on_link = far.on_obstacle = far.normal = Eigen::Vector3d::Constant(std::nan(""));
          track_minimum(out, l, o);
          continue;
        }
      }
      const collision::PairObstacle obstacle{&g, impl_->fcl_obstacles[size_t(o)].get()};
      collision::pair_function(backend, shape, g.shape)(link, obstacle, out.at(l, o));
      track_minimum(out, l, o);
    }
  }
}

}  // namespace rrlab
