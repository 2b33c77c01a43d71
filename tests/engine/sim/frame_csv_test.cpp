// The frame CSV (sim/frame_csv.hpp): columns from the field table, one per number.
#include <rrlab/sim/frame_csv.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

namespace rrlab {
namespace {

size_t columns(const std::string& line) { return size_t(std::count(line.begin(), line.end(), ',')) + 1; }

TEST(FrameCsv, HeaderNamesEveryNumber) {
  const std::string live = frame_csv_header(2, {"lambda"}, FrameOrigin::live);
  EXPECT_EQ(live,
            "step,t,q1,q2,qdot1,qdot2,ee_x,ee_y,ee_z,ee_quat_w,ee_quat_x,ee_quat_y,ee_quat_z,target_x,target_y,"
            "target_z,task_error,orientation_error,min_distance,min_distance_link,collided,min_self_distance,"
            "self_link_a,self_link_b,self_collided,joint_limit_margin,"
            "manipulability,condition_number,step_us,lambda\n");
  const std::string stored = frame_csv_header(2, {"lambda"}, FrameOrigin::stored);
  EXPECT_EQ(stored.find("step_us"), std::string::npos);
  EXPECT_EQ(columns(stored) + 1, columns(live));
}

TEST(FrameCsv, RowsMatchTheHeader) {
  Frame f;
  f.step = 4;
  f.t = 0.04;
  f.q = Eigen::Vector2d(0.5, -0.25);
  f.qdot = Eigen::Vector2d(1, 2);
  f.min_distance = std::numeric_limits<double>::infinity();
  f.min_distance_link = 1;
  f.collided = true;
  f.diagnostics = Eigen::VectorXd::Constant(1, 0.125);
  for (const FrameOrigin origin : {FrameOrigin::live, FrameOrigin::stored}) {
    std::string row;
    append_frame_csv(f, origin, row);
    EXPECT_EQ(columns(row), columns(frame_csv_header(2, {"lambda"}, origin)));
    EXPECT_EQ(row.rfind("4,0.04,0.5,-0.25,1,2,", 0), 0u) << row;
    // orientation_error 0, min_distance empty (inf), min_distance_link 2 (1-based), collided 1
    EXPECT_NE(row.find(",0,,2,1,"), std::string::npos) << row;
    EXPECT_EQ(row.back(), '\n');
    EXPECT_NE(row.find(",0.125\n"), std::string::npos) << row;
  }
}

}  // namespace
}  // namespace rrlab
