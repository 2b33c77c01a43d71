#include "storage/frame_codec.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>

namespace rrlab::storage {
namespace {

Frame sample_frame() {
  Frame f;
  f.step = 42;
  f.t = 0.42;
  f.q = Eigen::VectorXd::LinSpaced(7, -1.0, 1.0);
  f.qdot = Eigen::VectorXd::LinSpaced(7, 0.1, 0.7);
  f.ee_position = {1.0 / 3.0, -2.0, 1e-300};
  f.ee_orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()));
  f.target = {0.1, 0.2, 0.3};
  f.task_error = 1e-7;
  f.orientation_error = 0;
  f.min_distance = std::numeric_limits<double>::infinity();
  f.min_distance_link = -1;
  f.collided = true;
  f.joint_limit_margin = -0.0;
  f.manipulability = 0.5;
  f.condition_number = std::numeric_limits<double>::quiet_NaN();
  f.diagnostics = Eigen::Vector3d(1, 2, 3);
  return f;
}

TEST(FrameCodec, RoundTripIsBitExact) {
  const Frame f = sample_frame();
  const std::string packed = pack_frame(f);
  EXPECT_EQ(packed.size(), 16u + 8u * (19u + 14u + 3u));
  const Frame back = unpack_frame(packed);
  EXPECT_EQ(back.step, 42);
  EXPECT_EQ(std::memcmp(back.q.data(), f.q.data(), 7 * sizeof(double)), 0);
  EXPECT_TRUE(std::isinf(back.min_distance));
  EXPECT_TRUE(std::isnan(back.condition_number));
  EXPECT_TRUE(std::signbit(back.joint_limit_margin));  // -0.0 kept
  EXPECT_EQ(back.min_distance_link, -1);
  EXPECT_TRUE(back.collided);
  EXPECT_EQ(pack_frame(back), packed);  // packing the unpacked frame gives the same bytes
}

TEST(FrameCodec, RejectsBlobsOfTheWrongSize) {
  std::string packed = pack_frame(sample_frame());
  EXPECT_THROW(unpack_frame(packed.substr(0, packed.size() - 1)), std::runtime_error);
  EXPECT_THROW(unpack_frame(""), std::runtime_error);
  packed[0] = char(0xff);  // absurd dof
  EXPECT_THROW(unpack_frame(packed), std::runtime_error);
}

// Found by tests/fuzz/frame_fuzz.cpp: a link index beyond int was cast to int
// (undefined behaviour); a corrupt blob is now an error like a wrong size.
TEST(FrameCodec, RejectsALinkIndexThatIsNotOne) {
  const std::string packed = pack_frame(sample_frame());
  const size_t link_offset = 16 + 8 * (1 + 7 + 7 + 3 + 4 + 3 + 3);  // step, t, q, qdot, ee, quat, target, 3 metrics
  for (const double bad : {5.04759e+223, -2.0, 0.5, std::numeric_limits<double>::quiet_NaN()}) {
    std::string corrupt = packed;
    std::memcpy(corrupt.data() + link_offset, &bad, sizeof bad);
    EXPECT_THROW(unpack_frame(corrupt), std::runtime_error) << bad;
  }
  std::string fine = packed;
  const double link = 6;
  std::memcpy(fine.data() + link_offset, &link, sizeof link);
  EXPECT_EQ(unpack_frame(fine).min_distance_link, 6);
}

TEST(FrameCodec, JsonNamesDiagnosticsAndNullsNonFinite) {
  const nlohmann::json j = frame_to_json(sample_frame(), {"a", "b"});
  EXPECT_EQ(j["diagnostics"]["a"], 1.0);
  EXPECT_EQ(j["diagnostics"]["d3"], 3.0);  // undeclared name
  EXPECT_TRUE(j["min_distance"].is_null());
  EXPECT_TRUE(j["condition_number"].is_null());
  EXPECT_EQ(j["q"].size(), 7u);
}

}  // namespace
}  // namespace rrlab::storage
