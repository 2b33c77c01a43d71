// Self pairs by link shape: capsule–capsule (closest points of the axes,
// minus both radii), capsule–mesh (the capsule's axis against the mesh's
// tree, as a mesh obstacle), mesh–mesh (FCL).
#include <rrlab/collision/self_collision.hpp>

#include <cmath>

#include <rrlab/collision/fcl_pairs.hpp>
#include <rrlab/collision/link_obstacle_distance.hpp>
#include <rrlab/collision/mesh_distance.hpp>
#include <rrlab/collision/segment_geometry.hpp>

namespace rrlab {

using Eigen::Vector3d;

namespace {

struct MeshLink {
  std::shared_ptr<collision::MeshBvh> bvh;
  bool closed = false;
  Eigen::AlignedBox3d bounds;
};

}  // namespace

struct SelfCollisionWorld::Impl {
  std::vector<SelfPair> pairs;
  std::vector<double> radius;
  std::vector<int> last_joint;
  std::vector<MeshLink> mesh;  // bvh null for a capsule link

  const Eigen::Isometry3d& pose(const KinematicsData& kin, int link) const {
    return kin.joint_frames[size_t(last_joint[size_t(link)])];
  }

  void capsules(const KinematicsData& kin, SelfPairDistance& out) const {
    const int a = out.pair.a, b = out.pair.b;
    collision::closest_points_segments(kin.link_start.col(a), kin.link_end.col(a), kin.link_start.col(b),
                                       kin.link_end.col(b), out.on_a, out.on_b);
    const Vector3d across = out.on_a - out.on_b;
    const double gap = across.norm();
    out.normal = gap > collision::kTouching ? Vector3d(across / gap)
                                             : collision::any_perpendicular(kin.link_end.col(a) - kin.link_start.col(a));
    out.distance = gap - radius[size_t(a)] - radius[size_t(b)];
  }

  // Capsule `capsule` against mesh link `meshed`; the normal points mesh -> capsule.
  void capsule_mesh(const KinematicsData& kin, int capsule, int meshed, Vector3d& on_capsule, Vector3d& on_mesh,
                    Vector3d& normal, double& distance) const {
    const MeshLink& m = mesh[size_t(meshed)];
    const Eigen::Isometry3d& p = pose(kin, meshed);
    LinkObstacleDistance d;
    collision::segment_mesh(*m.bvh, m.closed, m.bounds, p.linear(), p.translation(), kin.link_start.col(capsule),
                            kin.link_end.col(capsule), d);
    on_capsule = d.on_link;
    on_mesh = d.on_obstacle;
    normal = d.normal;
    distance = d.distance - radius[size_t(capsule)];
  }

  void measure(const KinematicsData& kin, SelfPairDistance& out) const {
    const int a = out.pair.a, b = out.pair.b;
    const bool mesh_a = bool(mesh[size_t(a)].bvh), mesh_b = bool(mesh[size_t(b)].bvh);
    if (!mesh_a && !mesh_b) return capsules(kin, out);
    if (!mesh_a) return capsule_mesh(kin, a, b, out.on_a, out.on_b, out.normal, out.distance);
    if (!mesh_b) {
      capsule_mesh(kin, b, a, out.on_b, out.on_a, out.normal, out.distance);
      out.normal = -out.normal;
      return;
    }
    out.distance = collision::fcl_mesh_mesh(*mesh[size_t(a)].bvh, pose(kin, a), *mesh[size_t(b)].bvh, pose(kin, b),
                                            out.on_a, out.on_b);
    const Vector3d across = out.on_a - out.on_b;
    out.normal = across.norm() > collision::kTouching ? Vector3d(across.normalized()) : Vector3d(Vector3d::UnitZ());
  }
};

SelfCollisionWorld::SelfCollisionWorld(const Model& model) : impl_(std::make_unique<Impl>()) {
  impl_->pairs = model.self_pairs;
  for (const Link& link : model.links) {
    impl_->radius.push_back(link.radius);
    impl_->last_joint.push_back(link.last_joint);
    MeshLink m;
    if (link.mesh) {
      m.bvh = collision::make_bvh(*link.mesh);
      m.closed = collision::closed_mesh(*link.mesh);
      for (const Vector3d& v : link.mesh->vertices) m.bounds.extend(v);
    }
    impl_->mesh.push_back(std::move(m));
  }
}

SelfCollisionWorld::~SelfCollisionWorld() = default;

bool SelfCollisionWorld::empty() const { return impl_->pairs.empty(); }

void SelfCollisionWorld::compute(const KinematicsData& kin, SelfDistanceTable& out) const {
  out.pairs.resize(impl_->pairs.size());
  out.min_distance = std::numeric_limits<double>::infinity();
  out.min_pair = -1;
  for (size_t i = 0; i < impl_->pairs.size(); ++i) {
    SelfPairDistance& d = out.pairs[i];
    d.pair = impl_->pairs[i];
    impl_->measure(kin, d);
    if (d.distance < out.min_distance) {
      out.min_distance = d.distance;
      out.min_pair = int(i);
    }
  }
}

double min_self_distance(const Model& model, const Eigen::VectorXd& q) {
  if (model.self_pairs.empty()) return std::numeric_limits<double>::infinity();
  KinematicsData kin(model);
  forward_kinematics(model, q, kin);
  SelfCollisionWorld world(model);
  SelfDistanceTable table;
  world.compute(kin, table);
  return table.min_distance;
}

}  // namespace rrlab
