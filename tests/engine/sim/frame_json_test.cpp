// The one JSON shape of a frame (sim/frame_json.hpp).
#include <rrlab/sim/frame_json.hpp>

#include <gtest/gtest.h>

#include <limits>
#include <nlohmann/json.hpp>

namespace rrlab {
namespace {

Frame sample() {
  Frame f;
  f.step = 3;
  f.t = 0.1 + 0.2;  // 0.30000000000000004: exact text keeps every digit
  f.q = Eigen::Vector3d(1.0 / 3.0, -0.5, 2);
  f.qdot = Eigen::Vector3d(0, std::numeric_limits<double>::infinity(), 1);
  f.min_distance = std::numeric_limits<double>::infinity();
  f.min_distance_link = -1;
  f.step_us = 12.5;
  f.diagnostics = Eigen::Vector2d(0.25, std::numeric_limits<double>::quiet_NaN());
  return f;
}

nlohmann::json members(const Frame& f, FrameOrigin origin, int digits) {
  std::string text = "{";
  append_frame_json_members(f, origin, digits, text);
  text += '}';
  return nlohmann::json::parse(text);
}

TEST(FrameJson, LiveFramesCarryEveryField) {
  Frame f = sample();
  f.target_orientation = Eigen::Quaterniond::Identity();
  const nlohmann::json j = members(f, FrameOrigin::live, 0);
  EXPECT_EQ(j["step"], 3);
  EXPECT_EQ(j["t"].get<double>(), 0.1 + 0.2);
  EXPECT_EQ(j["q"][0].get<double>(), 1.0 / 3.0);
  EXPECT_TRUE(j["qdot"][1].is_null());
  EXPECT_EQ(j["ee_quat"], nlohmann::json({1.0, 0.0, 0.0, 0.0}));
  EXPECT_EQ(j["target_quat"], nlohmann::json({1.0, 0.0, 0.0, 0.0}));
  EXPECT_TRUE(j["metrics"]["min_distance"].is_null());
  EXPECT_EQ(j["metrics"]["min_distance_link"], 0);
  EXPECT_EQ(j["metrics"]["collided"], false);
  EXPECT_EQ(j["metrics"]["step_us"], 12.5);
  EXPECT_EQ(j["diagnostics"][0], 0.25);
  EXPECT_TRUE(j["diagnostics"][1].is_null());
  EXPECT_EQ(j.size(), 10u);  // step t q qdot ee ee_quat target target_quat metrics diagnostics
  EXPECT_EQ(j["metrics"].size(), 13u);
}

TEST(FrameJson, StoredFramesLeaveOutWhatIsNotStored) {
  Frame f = sample();
  f.target_orientation = Eigen::Quaterniond::Identity();
  const nlohmann::json j = members(f, FrameOrigin::stored, 0);
  EXPECT_FALSE(j.contains("target_quat"));
  EXPECT_FALSE(j["metrics"].contains("step_us"));
  EXPECT_EQ(j["metrics"].size(), 12u);
}

TEST(FrameJson, DigitsRoundForDrawing) {
  const nlohmann::json j = members(sample(), FrameOrigin::live, 7);
  EXPECT_EQ(j["q"][0].get<double>(), 0.3333333);
  EXPECT_EQ(j["t"].get<double>(), 0.3);
}

}  // namespace
}  // namespace rrlab
