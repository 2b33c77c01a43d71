#include <rrlab/methods/direct_search_joint_sets.hpp>

#include <algorithm>
#include <bitset>
#include <cmath>

namespace rrlab::kapoor {

namespace {
constexpr int kDirectSearchPower3[JointSets::kMaxPerturbed] = {1, 3, 9, 27, 81, 243};
}  // namespace

JointSets::JointSets(int n, int m) : n_(n), m_(m), square_block_(m, m) { block_.assign(n_, 0); }

void JointSets::choose(long mask) {
  const int allowed = std::min(kMaxPerturbed, std::max(0, n_ - m_));
  mask_bits_ = 0;
  int count = 0;
  for (int i = 0; i < n_ && i < 64; ++i)
    if (((mask >> i) & 1) && count < allowed) mask_bits_ |= 1ULL << i, ++count;
  use(mask_bits_);
  alternative_block_ = Eigen::MatrixXd::Zero(m_, std::max(1, block_count_));
  // every other set of as many perturbed joints, for the block switch
  alternatives_.clear();
  if (block_count_ >= m_ && n_ <= 20) {
    for (unsigned long long bits = 0; bits < (1ULL << n_); ++bits)
      if (static_cast<int>(std::bitset<64>(bits).count()) == count) alternatives_.push_back(bits);
  }
}

void JointSets::use(unsigned long long bits) {
  current_bits_ = bits;
  perturbed_count_ = 0;
  block_count_ = 0;
  for (int i = 0; i < n_; ++i) {
    if (i < 64 && ((bits >> i) & 1))
      perturbed_[perturbed_count_++] = i;
    else
      block_[block_count_++] = i;
  }
}

int JointSets::option_of_sequence(int s) const {
  int j = 0;
  for (int i = perturbed_count_ - 1; i >= 0; --i) j += (s % 3) * kDirectSearchPower3[i], s /= 3;
  return j;
}

unsigned long long JointSets::largest_determinant_set(const Eigen::MatrixXd& jacobian, unsigned long long required) {
  double best = -1;
  bool best_has_required = false;
  unsigned long long best_bits = mask_bits_;
  for (unsigned long long bits : alternatives_) {
    const bool has_required = (bits & required) == required;
    if (best_has_required && !has_required) continue;
    int columns[64], c = 0;
    for (int i = 0; i < n_; ++i)
      if (!((bits >> i) & 1)) columns[c++] = i;
    if (block_count_ == m_) {
      lu_.compute_columns(jacobian, columns);  // |det J_b|, in place
    } else {
      for (int k = 0; k < c; ++k) alternative_block_.col(k) = jacobian.col(columns[k]);
      square_block_.noalias() = alternative_block_ * alternative_block_.transpose();
      lu_.compute(square_block_);  // det(J_b J_bᵀ)
    }
    double det = std::abs(lu_.determinant());
    if (!std::isfinite(det)) det = 0;  // a block of non-finite entries is no candidate
    if (det > best || (has_required && !best_has_required)) best = det, best_bits = bits, best_has_required = has_required;
  }
  return best_bits;
}

unsigned long long JointSets::out_of_range_bits(const Eigen::MatrixXd& options, const JointLimits& limits) const {
  unsigned long long bits = 0;
  const int count = option_count();
  for (int j = 0; j < count; ++j)
    for (int i = 0; i < n_ && i < 64; ++i)
      if (options(i, j) < limits.lower[i] || options(i, j) > limits.upper[i]) bits |= 1ULL << i;
  return bits;
}

}  // namespace rrlab::kapoor
