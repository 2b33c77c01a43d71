// Kapoor, Cetin & Tesar (1998) §3.1: which joints a direct-search step
// perturbs and which form the block J_b that meets the end-effector
// constraint (the method is direct_search.cpp).
//  - the perturbed joints are the set bits of `perturb_mask` (bit i−1:
//    joint i), at most n − m of them and at most 6 (729 options); default
//    joints 1, 2, 3, 5 as in the paper's 81-option example. The block is
//    every joint not perturbed.
//  - the options: the k perturbed joints take −Δ, 0, +Δ, 3^k combinations;
//    option j's base-3 digits (lowest: the first perturbed joint) say which.
//  - the block switch's choice: of the sets of as many perturbed joints, the
//    one whose block has the largest |det J_b| (det J_b J_bᵀ for a wide
//    block), which §3.1 calls desirable but did not employ.
#pragma once

#include <Eigen/Core>
#include <vector>

#include <rrlab/model/model.hpp>
#include <rrlab/util/small_lu.hpp>

namespace rrlab::kapoor {

class JointSets {
 public:
  static constexpr int kMaxPerturbed = 6;
  static constexpr int kMaxOptions = 729;  // 3^6

  // n joints, m task rows.
  JointSets(int n, int m);

  // Perturbed joints: the mask's set bits (joint index < n), at most n − m
  // and 6; uses that set and lists every other set of as many joints (for
  // the block switch). May allocate; steady-state steps do not.
  void choose(long mask);
  // Perturbs the joints of `bits`; the others form the block.
  void use(unsigned long long bits);

  unsigned long long mask_bits() const { return mask_bits_; }
  unsigned long long current_bits() const { return current_bits_; }
  bool has_alternatives() const { return !alternatives_.empty(); }
  int perturbed_count() const { return perturbed_count_; }
  int perturbed(int i) const { return perturbed_[i]; }
  int block_count() const { return block_count_; }
  int block(int c) const { return block_[c]; }
  const int* block_joints() const { return block_.data(); }

  // 3^k options for k perturbed joints.
  int option_count() const {
    int count = 1;
    for (int i = 0; i < perturbed_count_; ++i) count *= 3;
    return count;
  }
  // The option index j of the s-th generated option: s's base-3 digits in
  // reverse (the first perturbed joint is j's lowest digit, s's highest).
  int option_of_sequence(int s) const;

  // The perturbed set whose block has the largest |det J_b| (square block,
  // §3.1) or, for a wide block, the largest det(J_b J_bᵀ) = Π σ² (the same
  // order for a square one).
  // Sets whose perturbed joints include `required` come first (any set when none does).
  unsigned long long largest_determinant_set(const Eigen::MatrixXd& jacobian, unsigned long long required);

  // Joints outside their range in some generated option (options: one per column).
  unsigned long long out_of_range_bits(const Eigen::MatrixXd& options, const JointLimits& limits) const;

 private:
  int n_, m_;
  unsigned long long mask_bits_ = 0, current_bits_ = 0;
  int perturbed_[kMaxPerturbed] = {}, perturbed_count_ = 0;
  std::vector<int> block_;  // the non-perturbed joints (n entries reserved)
  int block_count_ = 0;
  std::vector<unsigned long long> alternatives_;
  SmallLu lu_;
  Eigen::MatrixXd alternative_block_, square_block_;
};

}  // namespace rrlab::kapoor
