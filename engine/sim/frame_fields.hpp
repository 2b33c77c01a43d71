// What a frame holds, as one table: every writer of frames (the stored blob,
// the CSV, the JSON of the REST API and of the WebSocket stream, the field
// list of GET /api/frame-fields that the dashboard and the OpenAPI document
// follow) walks it, so that a field is added in one place and every output
// agrees on its name, its unit and its order.
//
// Adding a field: a member of Frame (sim/frame.hpp), one row of
// RRLAB_FRAME_FIELDS below, the code that computes it (sim/simulator.cpp) and
// its row in docs/api.md (a test compares the two). A new blob field takes
// `since` = kFrameBlobVersion + 1, and kFrameBlobVersion is raised: older
// blobs are still read (storage/frame_codec.cpp).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include <rrlab/sim/frame.hpp>

namespace rrlab {

enum class FrameFieldKind : std::uint8_t {
  count,        // an integer (step)
  number,       // one double
  flag,         // a bool: 1.0 / 0.0 in the blob, true / false in JSON, 1 / 0 in CSV
  link,         // a link index, -1 for none: written 1-based, 0 for none
  joints,       // one double per joint
  vec3,         // x y z
  quaternion,   // w x y z
  diagnostics,  // the method's named scalars (their names travel beside the frames)
};

// Which outputs carry a field. JSON is both the stream's frame and a stored
// frame of GET /api/runs/{id}/frames; a stored frame has only blob fields.
enum FrameOutput : unsigned {
  kFrameBlob = 1u,  // stored: deterministic, compared bit for bit by re-simulation
  kFrameCsv = 2u,
  kFrameJson = 4u,
};
inline constexpr unsigned kAllFrameOutputs = kFrameBlob | kFrameCsv | kFrameJson;
inline constexpr unsigned kLiveOnly = kFrameCsv | kFrameJson;  // measured, not deterministic: never stored

// The stored blob's format version (storage/frame_codec.hpp): 1 had no
// version word, 2 has one and the same fields, 3 adds the self-collision
// fields. A blob holds the fields whose `since` is at most its version, in
// table order, so a new field may sit anywhere in the table.
inline constexpr int kFrameBlobVersion = 3;

// The table. X(id, member of Frame, kind, metric: inside JSON's "metrics",
// outputs, blob version it appears from, unit, description), in the order
// every output writes them; the blob's order is this one (its layout must not
// change: stored runs are read back and re-simulated). The metrics are
// consecutive (the JSON writer opens "metrics" once).
#define RRLAB_FRAME_FIELDS(X)                                                                                       \
  X(step, step, count, false, kAllFrameOutputs, 1, "", "step index")                                                \
  X(t, t, number, false, kAllFrameOutputs, 1, "s", "time")                                                          \
  X(q, q, joints, false, kAllFrameOutputs, 1, "rad|m", "joint positions at t")                                      \
  X(qdot, qdot, joints, false, kAllFrameOutputs, 1, "rad/s|m/s", "joint velocities applied over [t, t + dt]")       \
  X(ee, ee_position, vec3, false, kAllFrameOutputs, 1, "m", "end-effector position")                                \
  X(ee_quat, ee_orientation, quaternion, false, kAllFrameOutputs, 1, "", "end-effector orientation (w x y z)")      \
  X(target, target, vec3, false, kAllFrameOutputs, 1, "m", "desired position at t")                                 \
  X(target_quat, target_orientation, quaternion, false, kFrameJson, 0, "",                                          \
    "desired orientation at t (pose tasks, live frames only)")                                                      \
  X(task_error, task_error, number, true, kAllFrameOutputs, 1, "m", "position error norm")                          \
  X(orientation_error, orientation_error, number, true, kAllFrameOutputs, 1, "rad",                                 \
    "orientation error angle (pose tasks)")                                                                         \
  X(min_distance, min_distance, number, true, kAllFrameOutputs, 1, "m",                                             \
    "signed distance from the arm to the nearest obstacle (null without obstacles)")                                \
  X(min_distance_link, min_distance_link, link, true, kAllFrameOutputs, 1, "",                                      \
    "the link nearest an obstacle, 1-based (0: none)")                                                              \
  X(collided, collided, flag, true, kAllFrameOutputs, 1, "", "the arm touches an obstacle")                         \
  X(min_self_distance, min_self_distance, number, true, kAllFrameOutputs, 3, "m",                                   \
    "signed distance between the nearest two links checked for self-collision (null when none is)")                 \
  X(self_link_a, self_link_a, link, true, kAllFrameOutputs, 3, "", "the lower link of that pair, 1-based (0: none)") \
  X(self_link_b, self_link_b, link, true, kAllFrameOutputs, 3, "", "the higher link of that pair, 1-based (0: none)") \
  X(self_collided, self_collided, flag, true, kAllFrameOutputs, 3, "", "two links checked for self-collision touch") \
  X(joint_limit_margin, joint_limit_margin, number, true, kAllFrameOutputs, 1, "rad|m",                             \
    "smallest distance of a bounded joint to its limit (null if none)")                                             \
  X(manipulability, manipulability, number, true, kAllFrameOutputs, 1, "",                                          \
    "Yoshikawa's sqrt(det(J J^T)) of the task Jacobian")                                                            \
  X(condition_number, condition_number, number, true, kAllFrameOutputs, 1, "",                                      \
    "largest over smallest singular value of the task Jacobian")                                                    \
  X(step_us, step_us, number, true, kLiveOnly, 0, "us",                                                             \
    "compute time of the step (measured, not deterministic: live frames and `rrlab run --out` only)")               \
  X(diagnostics, diagnostics, diagnostics, false, kAllFrameOutputs, 1, "",                                          \
    "the method's named scalars, in the order of diagnostic_names")

enum class FrameFieldId : std::uint8_t {
#define RRLAB_FRAME_FIELD_ID(id, member, kind, metric, outputs, since, unit, description) id,
  RRLAB_FRAME_FIELDS(RRLAB_FRAME_FIELD_ID)
#undef RRLAB_FRAME_FIELD_ID
};

struct FrameField {
  FrameFieldId id;
  std::string_view name;  // JSON key; CSV column, or its prefix (q → q1..qn, ee → ee_x, ee_y, ee_z)
  std::string_view unit;  // "" for a pure number
  FrameFieldKind kind;
  bool metric;            // JSON: inside "metrics"
  unsigned outputs;       // FrameOutput bits
  int since;              // blob fields: the blob version that added it (0: not stored)
  std::string_view description;
};

inline constexpr std::array kFrameFields{
#define RRLAB_FRAME_FIELD_ROW(id, member, kind, metric, outputs, since, unit, description) \
  FrameField{FrameFieldId::id, #id, unit, FrameFieldKind::kind, metric, outputs, since, description},
    RRLAB_FRAME_FIELDS(RRLAB_FRAME_FIELD_ROW)
#undef RRLAB_FRAME_FIELD_ROW
};

namespace detail {
[[noreturn]] void throw_bad_frame_field(const char* field);

// An integer stored as a double, checked before the cast: casting a value
// beyond the target type is undefined behaviour (a corrupt blob).
inline long integer_value(double value, double low, double high, const char* field) {
  if (!(value >= low && value <= high) || value != std::floor(value)) throw_bad_frame_field(field);
  return long(value);
}

// A Frame member's numbers, by the member's type: a view of its own storage,
// or of `scratch` for scalars and quaternions (w x y z).
inline std::span<const double> one(double value, std::array<double, 4>& scratch) {
  scratch[0] = value;
  return {scratch.data(), 1};
}
inline std::span<const double> values_of(const double& v, std::array<double, 4>&) { return {&v, 1}; }
inline std::span<const double> values_of(long v, std::array<double, 4>& s) { return one(double(v), s); }
inline std::span<const double> values_of(int v, std::array<double, 4>& s) { return one(double(v), s); }
inline std::span<const double> values_of(bool v, std::array<double, 4>& s) { return one(v ? 1.0 : 0.0, s); }
inline std::span<const double> values_of(const Eigen::VectorXd& v, std::array<double, 4>&) {
  return {v.data(), size_t(v.size())};
}
inline std::span<const double> values_of(const Eigen::Vector3d& v, std::array<double, 4>&) { return {v.data(), 3}; }
inline std::span<const double> values_of(const Eigen::Quaterniond& r, std::array<double, 4>& s) {
  s = {r.w(), r.x(), r.y(), r.z()};
  return {s.data(), 4};
}
inline std::span<const double> values_of(const std::optional<Eigen::Quaterniond>& r, std::array<double, 4>& s) {
  return values_of(r.value_or(Eigen::Quaterniond::Identity()), s);
}

// The member's own doubles, for readers that copy numbers straight in; nullptr
// where the member is not a run of doubles.
inline double* storage_of(double& v) { return &v; }
inline double* storage_of(Eigen::VectorXd& v) { return v.data(); }
inline double* storage_of(Eigen::Vector3d& v) { return v.data(); }
template <typename T>
double* storage_of(T&) { return nullptr; }

// Sets the member from `v`; throws on a value it cannot hold.
inline void assign(long& m, std::span<const double> v, const char* name) {
  m = integer_value(v[0], -9007199254740992.0, 9007199254740992.0, name);
}
inline void assign(int& m, std::span<const double> v, const char* name) {  // a link index
  m = int(integer_value(v[0], -1, 1e6, name));
}
inline void assign(double& m, std::span<const double> v, const char*) { m = v[0]; }
inline void assign(bool& m, std::span<const double> v, const char*) { m = v[0] != 0.0; }
inline void assign(Eigen::VectorXd& m, std::span<const double> v, const char*) {
  if (size_t(m.size()) != v.size()) throw_bad_frame_field("size");
  for (size_t i = 0; i < v.size(); ++i) m[Eigen::Index(i)] = v[i];
}
inline void assign(Eigen::Vector3d& m, std::span<const double> v, const char*) { m = {v[0], v[1], v[2]}; }
inline void assign(Eigen::Quaterniond& m, std::span<const double> v, const char*) {
  m = Eigen::Quaterniond(v[0], v[1], v[2], v[3]);
}
inline void assign(std::optional<Eigen::Quaterniond>& m, std::span<const double> v, const char*) {
  m = Eigen::Quaterniond(v[0], v[1], v[2], v[3]);
}
}  // namespace detail

// The kind's name in the field list of GET /api/frame-fields.
inline constexpr std::string_view frame_field_kind_name(FrameFieldKind kind) {
  switch (kind) {
    case FrameFieldKind::count: return "count";
    case FrameFieldKind::number: return "number";
    case FrameFieldKind::flag: return "flag";
    case FrameFieldKind::link: return "link";
    case FrameFieldKind::joints: return "joints";
    case FrameFieldKind::vec3: return "vec3";
    case FrameFieldKind::quaternion: return "quaternion";
    case FrameFieldKind::diagnostics: return "diagnostics";
  }
  return "";
}

// Where the frame comes from: a stored frame (decoded from its blob) has only
// the blob's fields; a live one has them all.
enum class FrameOrigin : std::uint8_t { stored, live };

// Whether `output` for a frame of `origin` writes `field`. A live target_quat
// is written only when the task has one.
inline bool frame_writes(const FrameField& field, FrameOutput output, FrameOrigin origin, const Frame& frame) {
  if ((field.outputs & output) == 0) return false;
  if (origin == FrameOrigin::stored && (field.outputs & kFrameBlob) == 0) return false;
  if (field.id == FrameFieldId::target_quat) return frame.target_orientation.has_value();
  return true;
}

// The field's numbers in the frame, in order: a view of the frame's own
// storage, or of `scratch` for scalars and quaternions (w x y z).
inline std::span<const double> frame_values(const Frame& f, FrameFieldId id, std::array<double, 4>& scratch) {
  switch (id) {
#define RRLAB_FRAME_FIELD_VALUES(id, member, kind, metric, outputs, since, unit, description) \
  case FrameFieldId::id: return detail::values_of(f.member, scratch);
    RRLAB_FRAME_FIELDS(RRLAB_FRAME_FIELD_VALUES)
#undef RRLAB_FRAME_FIELD_VALUES
  }
  return {};
}

// How many numbers the field has in a frame of `dof` joints and `diagnostics` names.
inline constexpr int frame_value_count(FrameFieldKind kind, int dof, int diagnostics) {
  switch (kind) {
    case FrameFieldKind::joints: return dof;
    case FrameFieldKind::diagnostics: return diagnostics;
    case FrameFieldKind::vec3: return 3;
    case FrameFieldKind::quaternion: return 4;
    case FrameFieldKind::count:
    case FrameFieldKind::number:
    case FrameFieldKind::flag:
    case FrameFieldKind::link: return 1;
  }
  return 0;
}

// The frame's own doubles for a field of kind number, joints, vec3 or
// diagnostics (joints and diagnostics sized already), for readers that copy
// numbers straight in; nullptr for the other kinds (use set_frame_values).
inline double* frame_storage(Frame& f, FrameFieldId id) {
  switch (id) {
#define RRLAB_FRAME_FIELD_STORAGE(id, member, kind, metric, outputs, since, unit, description) \
  case FrameFieldId::id: return detail::storage_of(f.member);
    RRLAB_FRAME_FIELDS(RRLAB_FRAME_FIELD_STORAGE)
#undef RRLAB_FRAME_FIELD_STORAGE
  }
  return nullptr;
}

// Sets the field from `values` (frame_value_count of them); joints and
// diagnostics must already have their size. Throws std::runtime_error on a
// value the field cannot hold (a count or link that is not an integer in range).
inline void set_frame_values(Frame& f, FrameFieldId id, std::span<const double> v) {
  switch (id) {
#define RRLAB_FRAME_FIELD_SET(id, member, kind, metric, outputs, since, unit, description) \
  case FrameFieldId::id: detail::assign(f.member, v, #id); break;
    RRLAB_FRAME_FIELDS(RRLAB_FRAME_FIELD_SET)
#undef RRLAB_FRAME_FIELD_SET
  }
}

}  // namespace rrlab
