#include <rrlab/storage/frame_codec.hpp>

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
  f.min_self_distance = -0.015;
  f.self_link_a = 1;
  f.self_link_b = 4;
  f.self_collided = true;
  f.joint_limit_margin = -0.0;
  f.manipulability = 0.5;
  f.condition_number = std::numeric_limits<double>::quiet_NaN();
  f.diagnostics = Eigen::Vector3d(1, 2, 3);
  return f;
}

TEST(FrameCodec, RoundTripIsBitExact) {
  const Frame f = sample_frame();
  const std::string packed = pack_frame(f);
  EXPECT_EQ(packed.size(), 4u + 16u + 8u * (23u + 14u + 3u));  // version word, n, k, the fields
  const Frame back = unpack_frame(packed);
  EXPECT_EQ(back.step, 42);
  EXPECT_EQ(std::memcmp(back.q.data(), f.q.data(), 7 * sizeof(double)), 0);
  EXPECT_TRUE(std::isinf(back.min_distance));
  EXPECT_TRUE(std::isnan(back.condition_number));
  EXPECT_TRUE(std::signbit(back.joint_limit_margin));  // -0.0 kept
  EXPECT_EQ(back.min_distance_link, -1);
  EXPECT_TRUE(back.collided);
  EXPECT_EQ(back.min_self_distance, -0.015);
  EXPECT_EQ(back.self_link_a, 1);
  EXPECT_EQ(back.self_link_b, 4);
  EXPECT_TRUE(back.self_collided);
  EXPECT_EQ(pack_frame(back), packed);  // packing the unpacked frame gives the same bytes
}

// Found by tests/fuzz/frame_fuzz.cpp under UBSan: a frame without
// diagnostics (an empty vector, whose data() is null) was copied with memcpy
// from a null pointer, undefined even for zero bytes.
TEST(FrameCodec, RoundTripsAFrameWithoutDiagnosticsOrJoints) {
  Frame f = sample_frame();
  f.diagnostics.resize(0);
  const std::string packed = pack_frame(f);
  EXPECT_EQ(unpack_frame(packed).diagnostics.size(), 0);
  EXPECT_EQ(pack_frame(unpack_frame(packed)), packed);
  f.q.resize(0);
  f.qdot.resize(0);
  EXPECT_EQ(pack_frame(unpack_frame(pack_frame(f))), pack_frame(f));
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
  const size_t link_offset = 4 + 16 + 8 * (1 + 7 + 7 + 3 + 4 + 3 + 3);  // step, t, q, qdot, ee, quat, target, 3 metrics
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

// The layout stored runs were written in, spelled out field by field: the
// field table (sim/frame_fields.hpp) must keep producing these bytes, or
// stored runs no longer decode and re-simulations no longer match.
TEST(FrameCodec, BlobLayoutIsTheStoredOne) {
  const Frame f = sample_frame();
  std::string expected, expected_v3;  // versions 1 and 2, version 3
  const auto put = [&](auto value) {
    expected.append(reinterpret_cast<const char*>(&value), sizeof value);
    expected_v3.append(reinterpret_cast<const char*>(&value), sizeof value);
  };
  const auto put_v3 = [&](auto value) { expected_v3.append(reinterpret_cast<const char*>(&value), sizeof value); };
  put(std::uint32_t(7));
  put(std::uint32_t(3));
  put(std::int64_t(42));
  put(f.t);
  for (int i = 0; i < 7; ++i) put(f.q[i]);
  for (int i = 0; i < 7; ++i) put(f.qdot[i]);
  for (int i = 0; i < 3; ++i) put(f.ee_position[i]);
  for (const double c : {f.ee_orientation.w(), f.ee_orientation.x(), f.ee_orientation.y(), f.ee_orientation.z()})
    put(c);
  for (int i = 0; i < 3; ++i) put(f.target[i]);
  for (const double m : {f.task_error, f.orientation_error, f.min_distance, -1.0, 1.0}) put(m);
  for (const double m : {-0.015, 1.0, 4.0, 1.0}) put_v3(m);  // self distance, its links (0-based), self_collided
  for (const double m : {f.joint_limit_margin, f.manipulability, f.condition_number}) put(m);
  for (int i = 0; i < 3; ++i) put(f.diagnostics[i]);
  std::string v1;
  pack_frame(f, v1, 1);
  EXPECT_EQ(v1, expected);  // version 1: no version word
  const auto word = [](std::uint32_t version) {
    const std::uint32_t w = 0x52460000u | version;  // "RF", version
    return std::string(reinterpret_cast<const char*>(&w), sizeof w);
  };
  std::string v2;
  pack_frame(f, v2, 2);
  EXPECT_EQ(v2, word(2) + expected);  // version 2: the word, then the same fields
  EXPECT_EQ(pack_frame(f), word(3) + expected_v3);  // version 3: and the self-collision fields
}

// Runs stored before the blob had a version still read, as what they are;
// a blob of a version this build does not know is refused, naming it.
TEST(FrameCodec, ReadsEveryVersionItKnowsAndNamesOneItDoesNot) {
  const Frame f = sample_frame();
  std::string v1;
  pack_frame(f, v1, 1);
  EXPECT_EQ(frame_blob_version(v1), 1);
  EXPECT_EQ(frame_blob_version(pack_frame(f)), kFrameBlobVersion);
  for (int version = 1; version < kFrameBlobVersion; ++version) {
    std::string old, again;
    pack_frame(f, old, version);
    EXPECT_EQ(frame_blob_version(old), version);
    const Frame back = unpack_frame(old);
    EXPECT_TRUE(std::isnan(back.min_self_distance)) << "version " << version << " knows no self distance";
    EXPECT_FALSE(back.self_collided);
    pack_frame(back, again, version);
    EXPECT_EQ(again, old);  // read as what it is, written back the same
  }
  std::string future = pack_frame(f);
  future[0] = char(kFrameBlobVersion + 1);
  try {
    unpack_frame(future);
    FAIL() << "a future version was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("version " + std::to_string(kFrameBlobVersion + 1)), std::string::npos)
        << e.what();
  }
  std::string out;
  EXPECT_THROW(pack_frame(f, out, kFrameBlobVersion + 1), std::invalid_argument);
}

TEST(FrameCodec, StoredJsonIsTheStreamShapeWithExactValues) {
  std::string text;
  append_stored_frame_json(9, sample_frame(), text);
  const nlohmann::json j = nlohmann::json::parse(text);
  EXPECT_EQ(j["seq"], 9);
  EXPECT_EQ(j["step"], 42);
  EXPECT_EQ(j["diagnostics"], nlohmann::json({1.0, 2.0, 3.0}));  // an array, named by the run's diagnostic_names
  EXPECT_TRUE(j["metrics"]["min_distance"].is_null());
  EXPECT_TRUE(j["metrics"]["condition_number"].is_null());
  EXPECT_EQ(j["metrics"]["min_distance_link"], 0);  // 1-based, 0: none
  EXPECT_EQ(j["metrics"]["collided"], true);
  EXPECT_FALSE(j["metrics"].contains("step_us"));  // measured, not stored
  EXPECT_FALSE(j.contains("target_quat"));         // live frames only
  EXPECT_EQ(j["q"].size(), 7u);
  EXPECT_EQ(j["ee"][0].get<double>(), 1.0 / 3.0);  // exact: the shortest text that reads back the same
  EXPECT_EQ(j["ee"][2].get<double>(), 1e-300);
  EXPECT_EQ(j["metrics"]["task_error"].get<double>(), 1e-7);
}

}  // namespace
}  // namespace rrlab::storage
