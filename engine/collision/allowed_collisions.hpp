// The allowed-collision matrix: which link pairs are not checked for
// self-collision. Made once per robot as MoveIt's setup assistant makes its
// SRDF's disable list: adjacent links are never checked, and pairs in contact
// in (nearly) every sampled configuration are disabled as "always"; pairs
// that no sample brings into contact are listed but still checked (a rare
// contact is still a contact). Planar arms take the rule of their plane
// instead of samples: links i and j with |i − j| ≥ 2 may not touch.
#pragma once

#include <memory>
#include <stdexcept>
#include <vector>

#include <rrlab/model/model.hpp>

namespace rrlab {

enum class AllowedReason { adjacent, always, user };
const char* to_string(AllowedReason reason);

struct AllowedPair {
  SelfPair pair;
  AllowedReason reason = AllowedReason::adjacent;
};

struct AllowedCollisionMatrix {
  std::vector<AllowedPair> allowed;         // pairs not checked, and why
  std::vector<SelfPair> checked;            // every other pair (a < b, in order)
  std::vector<SelfPair> never_in_contact;   // checked pairs no sample brought into contact
  int samples = 0;                          // configurations sampled; 0: the planar rule
};

// The sampling's bounds (documented in docs/scenario-format.md, robot).
struct SelfCollisionLimits {
  static constexpr int max_links = 64;           // beyond: refused while self-collision is checked
  static constexpr int samples = 10000;          // configurations per robot (MoveIt's default density)
  static constexpr int mesh_samples = 1000;      // when a link is a mesh (FCL's mesh distance is slower)
  static constexpr double always_fraction = 0.95;  // in contact in at least this share: "always"
  static constexpr std::uint64_t seed = 1;       // the samples are the same on every run
};

// A robot the matrix cannot be made for (too many links).
class SelfCollisionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The matrix of a model (its geometry and limits; self_pairs ignored), made
// once per distinct robot and cached for the process (thread safe).
std::shared_ptr<const AllowedCollisionMatrix> allowed_collision_matrix(const Model& model);

// Sets model.self_pairs: the matrix's checked pairs less `user_allowed` (a
// scenario's robot.allowed_collisions); none when `enabled` is false (and
// then no matrix is made). Throws SelfCollisionError past the link limit.
void assign_self_pairs(Model& model, bool enabled = true, const std::vector<SelfPair>& user_allowed = {});

}  // namespace rrlab
