// What a frame holds, as one table: every writer of frames (the stored blob,
// the CSV, the JSON of the REST API and of the WebSocket stream) walks it, so
// that a field is added in one place and every output agrees on its name, its
// unit and its order.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <string_view>

#include "sim/frame.hpp"

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

enum class FrameFieldId : std::uint8_t {
  step, t, q, qdot, ee, ee_quat, target, target_quat,
  task_error, orientation_error, min_distance, min_distance_link, collided,
  joint_limit_margin, manipulability, condition_number, step_us, diagnostics,
};

struct FrameField {
  FrameFieldId id;
  std::string_view name;  // JSON key; CSV column, or its prefix (q → q1..qn, ee → ee_x, ee_y, ee_z)
  std::string_view unit;  // "" for a pure number
  FrameFieldKind kind;
  bool metric;            // JSON: inside "metrics"
  unsigned outputs;       // FrameOutput bits
  std::string_view description;
};

inline constexpr unsigned kAllFrameOutputs = kFrameBlob | kFrameCsv | kFrameJson;

// In the order every output writes them; the blob's order is this one (its
// layout must not change: stored runs are read back and re-simulated).
inline constexpr std::array<FrameField, 18> kFrameFields{{
    {FrameFieldId::step, "step", "", FrameFieldKind::count, false, kAllFrameOutputs, "step index"},
    {FrameFieldId::t, "t", "s", FrameFieldKind::number, false, kAllFrameOutputs, "time"},
    {FrameFieldId::q, "q", "rad|m", FrameFieldKind::joints, false, kAllFrameOutputs, "joint positions at t"},
    {FrameFieldId::qdot, "qdot", "rad/s|m/s", FrameFieldKind::joints, false, kAllFrameOutputs,
     "joint velocities applied over [t, t + dt]"},
    {FrameFieldId::ee, "ee", "m", FrameFieldKind::vec3, false, kAllFrameOutputs, "end-effector position"},
    {FrameFieldId::ee_quat, "ee_quat", "", FrameFieldKind::quaternion, false, kAllFrameOutputs,
     "end-effector orientation (w x y z)"},
    {FrameFieldId::target, "target", "m", FrameFieldKind::vec3, false, kAllFrameOutputs, "desired position at t"},
    {FrameFieldId::target_quat, "target_quat", "", FrameFieldKind::quaternion, false, kFrameJson,
     "desired orientation at t (pose tasks, live frames only)"},
    {FrameFieldId::task_error, "task_error", "m", FrameFieldKind::number, true, kAllFrameOutputs,
     "position error norm"},
    {FrameFieldId::orientation_error, "orientation_error", "rad", FrameFieldKind::number, true, kAllFrameOutputs,
     "orientation error angle (pose tasks)"},
    {FrameFieldId::min_distance, "min_distance", "m", FrameFieldKind::number, true, kAllFrameOutputs,
     "signed distance from the arm to the nearest obstacle (null without obstacles)"},
    {FrameFieldId::min_distance_link, "min_distance_link", "", FrameFieldKind::link, true, kAllFrameOutputs,
     "the link nearest an obstacle, 1-based (0: none)"},
    {FrameFieldId::collided, "collided", "", FrameFieldKind::flag, true, kAllFrameOutputs,
     "the arm touches an obstacle"},
    {FrameFieldId::joint_limit_margin, "joint_limit_margin", "rad|m", FrameFieldKind::number, true,
     kAllFrameOutputs, "smallest distance of a bounded joint to its limit (null if none)"},
    {FrameFieldId::manipulability, "manipulability", "", FrameFieldKind::number, true, kAllFrameOutputs,
     "Yoshikawa's sqrt(det(J J^T)) of the task Jacobian"},
    {FrameFieldId::condition_number, "condition_number", "", FrameFieldKind::number, true, kAllFrameOutputs,
     "largest over smallest singular value of the task Jacobian"},
    {FrameFieldId::step_us, "step_us", "us", FrameFieldKind::number, true, kFrameCsv | kFrameJson,
     "compute time of the step (measured, not deterministic: live frames and `rrlab run --out` only)"},
    {FrameFieldId::diagnostics, "diagnostics", "", FrameFieldKind::diagnostics, false, kAllFrameOutputs,
     "the method's named scalars, in the order of diagnostic_names"},
}};

namespace detail {
inline std::span<const double> one(double value, std::array<double, 4>& scratch) {
  scratch[0] = value;
  return {scratch.data(), 1};
}

inline std::span<const double> quaternion(const Eigen::Quaterniond& r, std::array<double, 4>& scratch) {
  scratch = {r.w(), r.x(), r.y(), r.z()};
  return {scratch.data(), 4};
}

[[noreturn]] void throw_bad_frame_field(const char* field);

// An integer stored as a double, checked before the cast: casting a value
// beyond the target type is undefined behaviour (a corrupt blob).
inline long integer_value(double value, double low, double high, const char* field) {
  if (!(value >= low && value <= high) || value != std::floor(value)) throw_bad_frame_field(field);
  return long(value);
}
}  // namespace detail

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
    case FrameFieldId::step: return detail::one(double(f.step), scratch);
    case FrameFieldId::t: return detail::one(f.t, scratch);
    case FrameFieldId::q: return {f.q.data(), size_t(f.q.size())};
    case FrameFieldId::qdot: return {f.qdot.data(), size_t(f.qdot.size())};
    case FrameFieldId::ee: return {f.ee_position.data(), 3};
    case FrameFieldId::ee_quat: return detail::quaternion(f.ee_orientation, scratch);
    case FrameFieldId::target: return {f.target.data(), 3};
    case FrameFieldId::target_quat:
      return detail::quaternion(f.target_orientation.value_or(Eigen::Quaterniond::Identity()), scratch);
    case FrameFieldId::task_error: return detail::one(f.task_error, scratch);
    case FrameFieldId::orientation_error: return detail::one(f.orientation_error, scratch);
    case FrameFieldId::min_distance: return detail::one(f.min_distance, scratch);
    case FrameFieldId::min_distance_link: return detail::one(double(f.min_distance_link), scratch);
    case FrameFieldId::collided: return detail::one(f.collided ? 1.0 : 0.0, scratch);
    case FrameFieldId::joint_limit_margin: return detail::one(f.joint_limit_margin, scratch);
    case FrameFieldId::manipulability: return detail::one(f.manipulability, scratch);
    case FrameFieldId::condition_number: return detail::one(f.condition_number, scratch);
    case FrameFieldId::step_us: return detail::one(f.step_us, scratch);
    case FrameFieldId::diagnostics: return {f.diagnostics.data(), size_t(f.diagnostics.size())};
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
    case FrameFieldId::t: return &f.t;
    case FrameFieldId::q: return f.q.data();
    case FrameFieldId::qdot: return f.qdot.data();
    case FrameFieldId::ee: return f.ee_position.data();
    case FrameFieldId::target: return f.target.data();
    case FrameFieldId::task_error: return &f.task_error;
    case FrameFieldId::orientation_error: return &f.orientation_error;
    case FrameFieldId::min_distance: return &f.min_distance;
    case FrameFieldId::joint_limit_margin: return &f.joint_limit_margin;
    case FrameFieldId::manipulability: return &f.manipulability;
    case FrameFieldId::condition_number: return &f.condition_number;
    case FrameFieldId::step_us: return &f.step_us;
    case FrameFieldId::diagnostics: return f.diagnostics.data();
    case FrameFieldId::step:
    case FrameFieldId::ee_quat:
    case FrameFieldId::target_quat:
    case FrameFieldId::min_distance_link:
    case FrameFieldId::collided: return nullptr;
  }
  return nullptr;
}

// Sets the field from `values` (frame_value_count of them); joints and
// diagnostics must already have their size. Throws std::runtime_error on a
// value the field cannot hold (a count or link that is not an integer in range).
inline void set_frame_values(Frame& f, FrameFieldId id, std::span<const double> v) {
  const auto copy = [&](Eigen::VectorXd& to) {
    if (size_t(to.size()) != v.size()) detail::throw_bad_frame_field("size");
    for (size_t i = 0; i < v.size(); ++i) to[Eigen::Index(i)] = v[i];
  };
  switch (id) {
    case FrameFieldId::step: f.step = detail::integer_value(v[0], -9007199254740992.0, 9007199254740992.0, "step"); break;
    case FrameFieldId::t: f.t = v[0]; break;
    case FrameFieldId::q: copy(f.q); break;
    case FrameFieldId::qdot: copy(f.qdot); break;
    case FrameFieldId::ee: f.ee_position = {v[0], v[1], v[2]}; break;
    case FrameFieldId::ee_quat: f.ee_orientation = Eigen::Quaterniond(v[0], v[1], v[2], v[3]); break;
    case FrameFieldId::target: f.target = {v[0], v[1], v[2]}; break;
    case FrameFieldId::target_quat: f.target_orientation = Eigen::Quaterniond(v[0], v[1], v[2], v[3]); break;
    case FrameFieldId::task_error: f.task_error = v[0]; break;
    case FrameFieldId::orientation_error: f.orientation_error = v[0]; break;
    case FrameFieldId::min_distance: f.min_distance = v[0]; break;
    case FrameFieldId::min_distance_link:
      f.min_distance_link = int(detail::integer_value(v[0], -1, 1e6, "min_distance_link"));
      break;
    case FrameFieldId::collided: f.collided = v[0] != 0.0; break;
    case FrameFieldId::joint_limit_margin: f.joint_limit_margin = v[0]; break;
    case FrameFieldId::manipulability: f.manipulability = v[0]; break;
    case FrameFieldId::condition_number: f.condition_number = v[0]; break;
    case FrameFieldId::step_us: f.step_us = v[0]; break;
    case FrameFieldId::diagnostics: copy(f.diagnostics); break;
  }
}


}  // namespace rrlab
