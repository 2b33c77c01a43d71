// The matrix by sampling (or the planar rule), and its per-robot cache.
#include <rrlab/collision/allowed_collisions.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <mutex>
#include <numbers>
#include <string>

#include <rrlab/collision/mesh_loader.hpp>
#include <rrlab/collision/self_collision.hpp>
#include <rrlab/kinematics/kinematics.hpp>
#include <rrlab/util/rng.hpp>

namespace rrlab {

const char* to_string(AllowedReason reason) {
  switch (reason) {
    case AllowedReason::adjacent: return "adjacent";
    case AllowedReason::always: return "always";
    case AllowedReason::user: return "user";
  }
  return "?";
}

namespace {

// FNV-1a over the bytes that make a robot: two models with the same key
// have the same links, joints and limits.
class Fingerprint {
 public:
  template <typename T>
  void add(const T& value) {
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    for (unsigned char b : bytes) hash_ = (hash_ ^ b) * 0x100000001b3ULL;
  }
  void add(const Eigen::Isometry3d& pose) {
    for (int i = 0; i < 16; ++i) add(pose.matrix().data()[i]);
  }
  void add(const Eigen::VectorXd& v) {
    add(v.size());
    for (Eigen::Index i = 0; i < v.size(); ++i) add(v[i]);
  }
  std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xcbf29ce484222325ULL;
};

std::uint64_t robot_fingerprint(const Model& model) {
  Fingerprint f;
  f.add(int(model.kind));
  f.add(model.base);
  for (const Joint& j : model.joints) {
    f.add(int(j.type));
    f.add(j.pre);
    f.add(j.post);
    for (int k = 0; k < 3; ++k) f.add(j.axis[k]);
  }
  for (const Link& l : model.links) {
    f.add(l.last_joint);
    f.add(l.radius);
    f.add(l.mesh != nullptr);
    if (!l.mesh) continue;
    for (const Eigen::Vector3d& v : l.mesh->vertices)
      for (int k = 0; k < 3; ++k) f.add(v[k]);
    for (const Eigen::Vector3i& t : l.mesh->triangles)
      for (int k = 0; k < 3; ++k) f.add(t[k]);
  }
  f.add(model.limits.lower);
  f.add(model.limits.upper);
  return f.value();
}

// Planar: every pair two or more links apart is checked, except two links
// whose middle link is shorter than their radii together: its ends are
// both links' ends, so they touch in every configuration.
AllowedCollisionMatrix planar_matrix(const Model& model) {
  AllowedCollisionMatrix m;
  const int links = model.link_count();
  KinematicsData kin(model);
  forward_kinematics(model, Eigen::VectorXd::Zero(model.dof()), kin);
  for (int a = 0; a < links; ++a)
    for (int b = a + 1; b < links; ++b) {
      if (b == a + 1) {
        m.allowed.push_back({{a, b}, AllowedReason::adjacent});
        continue;
      }
      const double middle = (kin.link_end.col(a + 1) - kin.link_start.col(a + 1)).norm();
      if (b == a + 2 && middle <= model.links[size_t(a)].radius + model.links[size_t(b)].radius)
        m.allowed.push_back({{a, b}, AllowedReason::always});
      else
        m.checked.push_back({a, b});
    }
  return m;
}

// A joint's sampling range: its limits, or a turn either way (revolute),
// or the robot's reach (prismatic) where it has none.
void sampling_range(const Model& model, int j, double& lo, double& hi) {
  const double span = model.joints[size_t(j)].type == JointType::revolute ? std::numbers::pi : model.reach();
  lo = std::isfinite(model.limits.lower[j]) ? model.limits.lower[j] : -span;
  hi = std::isfinite(model.limits.upper[j]) ? model.limits.upper[j] : span;
}

AllowedCollisionMatrix sampled_matrix(const Model& model) {
  const int links = model.link_count();
  Model all = model;  // every non-adjacent pair, measured at each sample
  all.self_pairs.clear();
  AllowedCollisionMatrix m;
  for (int a = 0; a < links; ++a)
    for (int b = a + 1; b < links; ++b) {
      if (b == a + 1)
        m.allowed.push_back({{a, b}, AllowedReason::adjacent});
      else
        all.self_pairs.push_back({a, b});
    }
  const bool meshes = std::any_of(model.links.begin(), model.links.end(), [](const Link& l) { return l.mesh != nullptr; });
  m.samples = meshes ? SelfCollisionLimits::mesh_samples : SelfCollisionLimits::samples;
  if (all.self_pairs.empty()) return m;

  SelfCollisionWorld world(all);
  KinematicsData kin(all);
  SelfDistanceTable table;
  Eigen::VectorXd q(model.dof()), lo(model.dof()), hi(model.dof());
  for (int j = 0; j < model.dof(); ++j) sampling_range(model, j, lo[j], hi[j]);  // once, not per sample
  std::vector<int> contacts(all.self_pairs.size(), 0);
  Rng rng(SelfCollisionLimits::seed);
  for (int s = 0; s < m.samples; ++s) {
    for (int j = 0; j < model.dof(); ++j) q[j] = rng.uniform(lo[j], hi[j]);
    forward_kinematics(all, q, kin);
    world.compute(kin, table);
    for (size_t i = 0; i < table.pairs.size(); ++i)
      if (table.pairs[i].distance <= 0) ++contacts[i];
  }
  for (size_t i = 0; i < all.self_pairs.size(); ++i) {
    const SelfPair p = all.self_pairs[i];
    if (contacts[i] >= SelfCollisionLimits::always_fraction * m.samples) {
      m.allowed.push_back({p, AllowedReason::always});
      continue;
    }
    m.checked.push_back(p);
    if (contacts[i] == 0) m.never_in_contact.push_back(p);
  }
  std::sort(m.allowed.begin(), m.allowed.end(), [](const AllowedPair& x, const AllowedPair& y) {
    return x.pair.a != y.pair.a ? x.pair.a < y.pair.a : x.pair.b < y.pair.b;
  });
  return m;
}

AllowedCollisionMatrix make_matrix(const Model& model) {
  if (model.link_count() > SelfCollisionLimits::max_links)
    throw SelfCollisionError("the robot has " + std::to_string(model.link_count()) +
                             " links; self-collision is checked for at most " +
                             std::to_string(SelfCollisionLimits::max_links) +
                             " (set robot.self_collision to false to run it unchecked)");
  return model.kind == ModelKind::planar ? planar_matrix(model) : sampled_matrix(model);
}

// Generated families make a robot per case: the cache is bounded, and
// starts over when full (a matrix is cheap to make again).
constexpr size_t kCacheEntries = 512;

}  // namespace

std::shared_ptr<const AllowedCollisionMatrix> allowed_collision_matrix(const Model& model) {
  static std::mutex mutex;
  static std::map<std::uint64_t, std::shared_ptr<const AllowedCollisionMatrix>> cache;
  const std::uint64_t key = robot_fingerprint(model);
  {
    std::lock_guard<std::mutex> lock(mutex);
    const auto found = cache.find(key);
    if (found != cache.end()) return found->second;
  }
  auto matrix = std::make_shared<const AllowedCollisionMatrix>(make_matrix(model));  // outside the lock
  std::lock_guard<std::mutex> lock(mutex);
  if (cache.size() >= kCacheEntries) cache.clear();
  return cache.emplace(key, std::move(matrix)).first->second;
}

void assign_self_pairs(Model& model, bool enabled, const std::vector<SelfPair>& user_allowed) {
  model.self_pairs.clear();
  if (!enabled) return;
  const std::shared_ptr<const AllowedCollisionMatrix> matrix = allowed_collision_matrix(model);
  for (const SelfPair& p : matrix->checked)
    if (std::find(user_allowed.begin(), user_allowed.end(), p) == user_allowed.end()) model.self_pairs.push_back(p);
}

}  // namespace rrlab
