// The frame field table (sim/frame_fields.hpp): its invariants, its accessors
// against the Frame they read, and docs/api.md's table against it.
#include <rrlab/sim/frame_fields.hpp>

#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>

namespace rrlab {
namespace {

Frame filled_frame() {
  Frame f;
  f.step = 7;
  f.t = 0.07;
  f.q = Eigen::VectorXd::LinSpaced(4, 1, 4);
  f.qdot = Eigen::VectorXd::LinSpaced(4, 5, 8);
  f.ee_position = {9, 10, 11};
  f.ee_orientation = Eigen::Quaterniond(0.5, 0.5, -0.5, 0.5);
  f.target = {12, 13, 14};
  f.target_orientation = Eigen::Quaterniond(0, 1, 0, 0);
  f.task_error = 15;
  f.orientation_error = 16;
  f.min_distance = 17;
  f.min_distance_link = 2;
  f.collided = true;
  f.joint_limit_margin = 18;
  f.manipulability = 19;
  f.condition_number = 20;
  f.step_us = 21;
  f.diagnostics = Eigen::Vector2d(22, 23);
  return f;
}

TEST(FrameFields, NamesAreUniqueAndMetricsConsecutive) {
  std::set<std::string_view> names;
  int runs_of_metrics = 0;
  bool previous = false;
  for (const FrameField& field : kFrameFields) {
    EXPECT_TRUE(names.insert(field.name).second) << field.name;
    EXPECT_NE(field.outputs, 0u) << field.name;
    if (field.metric && !previous) ++runs_of_metrics;
    previous = field.metric;
  }
  EXPECT_EQ(runs_of_metrics, 1);  // the JSON writer opens "metrics" once
  // the ids are the table's positions, so a field is found by its id
  for (size_t i = 0; i < kFrameFields.size(); ++i) EXPECT_EQ(size_t(kFrameFields[i].id), i);
}

// Every field read, written back into an empty frame and read again: the
// accessors agree with each other and with the Frame's members.
TEST(FrameFields, ValuesRoundTripThroughSetAndStorage) {
  const Frame f = filled_frame();
  Frame g;
  g.q.resize(4);
  g.qdot.resize(4);
  g.diagnostics.resize(2);
  std::array<double, 4> a{}, b{};
  for (const FrameField& field : kFrameFields) {
    const std::span<const double> values = frame_values(f, field.id, a);
    EXPECT_EQ(int(values.size()), frame_value_count(field.kind, 4, 2)) << field.name;
    set_frame_values(g, field.id, values);
    const std::span<const double> back = frame_values(g, field.id, b);
    EXPECT_TRUE(std::equal(values.begin(), values.end(), back.begin(), back.end())) << field.name;
    if (double* storage = frame_storage(g, field.id)) {
      EXPECT_EQ(*storage, values[0]) << field.name;
    }
  }
  EXPECT_EQ(g.step, 7);
  EXPECT_EQ(g.min_distance_link, 2);
  EXPECT_TRUE(g.collided);
  EXPECT_EQ(g.ee_orientation.coeffs(), f.ee_orientation.coeffs());
  EXPECT_EQ(frame_values(f, FrameFieldId::ee_quat, a)[0], 0.5);  // w first
}

TEST(FrameFields, RefusesACountOrLinkThatIsNotAnInteger) {
  Frame f;
  for (const double bad : {0.5, -2.0, 1e300, std::numeric_limits<double>::quiet_NaN()})
    EXPECT_THROW(set_frame_values(f, FrameFieldId::min_distance_link, {&bad, 1}), std::runtime_error) << bad;
  const double huge = 1e17;
  EXPECT_THROW(set_frame_values(f, FrameFieldId::step, {&huge, 1}), std::runtime_error);
}

TEST(FrameFields, WhatEachSourceWrites) {
  Frame f = filled_frame();
  const auto writes = [&](FrameFieldId id, FrameOutput output, FrameOrigin origin) {
    return frame_writes(kFrameFields[size_t(id)], output, origin, f);
  };
  EXPECT_TRUE(writes(FrameFieldId::step_us, kFrameJson, FrameOrigin::live));
  EXPECT_FALSE(writes(FrameFieldId::step_us, kFrameJson, FrameOrigin::stored));
  EXPECT_TRUE(writes(FrameFieldId::target_quat, kFrameJson, FrameOrigin::live));
  EXPECT_FALSE(writes(FrameFieldId::target_quat, kFrameCsv, FrameOrigin::live));  // CSV columns are fixed per run
  f.target_orientation.reset();
  EXPECT_FALSE(writes(FrameFieldId::target_quat, kFrameJson, FrameOrigin::live));
}

// docs/api.md's frame table lists every field with the table's unit: a field
// added to the engine and not to the docs fails here.
TEST(FrameFields, DocumentedInTheApiDocs) {
  std::ifstream in(std::string(RRLAB_SOURCE_DIR) + "/docs/api.md");
  std::stringstream text;
  text << in.rdbuf();
  const std::string docs = text.str();
  const size_t begin = docs.find("<!-- frame-fields -->"), end = docs.find("<!-- /frame-fields -->");
  ASSERT_NE(begin, std::string::npos);
  ASSERT_NE(end, std::string::npos);
  const std::string table = docs.substr(begin, end - begin);
  int rows = 0;
  for (size_t at = table.find("\n| `"); at != std::string::npos; at = table.find("\n| `", at + 1)) ++rows;
  EXPECT_EQ(rows, int(kFrameFields.size()));
  for (const FrameField& field : kFrameFields) {
    std::string unit(field.unit.empty() ? "—" : field.unit);
    for (size_t bar = unit.find('|'); bar != std::string::npos; bar = unit.find('|', bar + 2)) unit.insert(bar, "\\");
    const std::string row = "| `" + std::string(field.metric ? "metrics." : "") + std::string(field.name) + "` | " +
                            unit + " | ";
    EXPECT_NE(table.find(row), std::string::npos) << "docs/api.md lacks the row " << row;
  }
}

}  // namespace
}  // namespace rrlab
