#include "storage/frame_codec.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace rrlab::storage {

static_assert(std::endian::native == std::endian::little, "the frame blob is little-endian");

namespace {

constexpr size_t kFixedDoubles = 1 + 3 + 4 + 3 + 8;  // t, ee, quat, target, 8 metrics

template <typename T>
void put(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

template <typename T>
T take(std::string_view& in) {
  if (in.size() < sizeof(T)) throw std::runtime_error("frame blob too short");
  T value;
  std::memcpy(&value, in.data(), sizeof(T));
  in.remove_prefix(sizeof(T));
  return value;
}

}  // namespace

void pack_frame(const Frame& f, std::string& out) {
  const auto n = std::uint32_t(f.q.size()), k = std::uint32_t(f.diagnostics.size());
  out.clear();
  out.reserve(16 + 8 * (kFixedDoubles + 2 * n + k));
  put(out, n);
  put(out, k);
  put(out, std::int64_t(f.step));
  put(out, f.t);
  for (std::uint32_t i = 0; i < n; ++i) put(out, f.q[i]);
  for (std::uint32_t i = 0; i < n; ++i) put(out, f.qdot[i]);
  for (int i = 0; i < 3; ++i) put(out, f.ee_position[i]);
  put(out, f.ee_orientation.w());
  put(out, f.ee_orientation.x());
  put(out, f.ee_orientation.y());
  put(out, f.ee_orientation.z());
  for (int i = 0; i < 3; ++i) put(out, f.target[i]);
  put(out, f.task_error);
  put(out, f.orientation_error);
  put(out, f.min_distance);
  put(out, double(f.min_distance_link));
  put(out, f.collided ? 1.0 : 0.0);
  put(out, f.joint_limit_margin);
  put(out, f.manipulability);
  put(out, f.condition_number);
  for (std::uint32_t i = 0; i < k; ++i) put(out, f.diagnostics[i]);
}

std::string pack_frame(const Frame& frame) {
  std::string out;
  pack_frame(frame, out);
  return out;
}

StoredFrame stored_frame(std::int64_t seq, const Frame& f, std::string packed) {
  return {seq, f.step, f.t, f.task_error, f.min_distance, f.collided, std::move(packed)};
}

Frame unpack_frame(std::string_view in) {
  const auto n = take<std::uint32_t>(in), k = take<std::uint32_t>(in);
  if (n > 4096 || k > 4096 || in.size() != 8 + 8 * (kFixedDoubles + 2 * size_t(n) + k))
    throw std::runtime_error("frame blob has the wrong size");
  Frame f;
  f.step = long(take<std::int64_t>(in));
  f.t = take<double>(in);
  f.q.resize(n);
  f.qdot.resize(n);
  for (std::uint32_t i = 0; i < n; ++i) f.q[i] = take<double>(in);
  for (std::uint32_t i = 0; i < n; ++i) f.qdot[i] = take<double>(in);
  for (int i = 0; i < 3; ++i) f.ee_position[i] = take<double>(in);
  f.ee_orientation.w() = take<double>(in);
  f.ee_orientation.x() = take<double>(in);
  f.ee_orientation.y() = take<double>(in);
  f.ee_orientation.z() = take<double>(in);
  for (int i = 0; i < 3; ++i) f.target[i] = take<double>(in);
  f.task_error = take<double>(in);
  f.orientation_error = take<double>(in);
  f.min_distance = take<double>(in);
  // a link index (-1: none) stored as a double: checked before the cast, which
  // is undefined behaviour for a value beyond int (a corrupt blob)
  const double link = take<double>(in);
  if (!(link >= -1 && link <= 1e6) || link != std::floor(link))
    throw std::runtime_error("frame blob has a bad min_distance_link");
  f.min_distance_link = int(link);
  f.collided = take<double>(in) != 0.0;
  f.joint_limit_margin = take<double>(in);
  f.manipulability = take<double>(in);
  f.condition_number = take<double>(in);
  f.diagnostics.resize(k);
  for (std::uint32_t i = 0; i < k; ++i) f.diagnostics[i] = take<double>(in);
  return f;
}

nlohmann::json frame_to_json(const Frame& f, const std::vector<std::string>& diagnostic_names) {
  nlohmann::json diagnostics = nlohmann::json::object();
  for (Eigen::Index i = 0; i < f.diagnostics.size(); ++i) {
    std::string name = "d";  // a name the frame's method did not declare
    if (size_t(i) < diagnostic_names.size())
      name = diagnostic_names[size_t(i)];
    else
      name.append(std::to_string(i + 1));
    diagnostics[name] = finite_or_null(f.diagnostics[i]);
  }
  const Eigen::Quaterniond& r = f.ee_orientation;
  return {{"step", f.step},
          {"t", f.t},
          {"q", finite_or_null(f.q)},
          {"qdot", finite_or_null(f.qdot)},
          {"ee", finite_or_null(Eigen::VectorXd(f.ee_position))},
          {"ee_quat", {r.w(), r.x(), r.y(), r.z()}},
          {"target", finite_or_null(Eigen::VectorXd(f.target))},
          {"task_error", finite_or_null(f.task_error)},
          {"orientation_error", finite_or_null(f.orientation_error)},
          {"min_distance", finite_or_null(f.min_distance)},
          {"min_distance_link", f.min_distance_link + 1},
          {"collided", f.collided},
          {"joint_limit_margin", finite_or_null(f.joint_limit_margin)},
          {"manipulability", finite_or_null(f.manipulability)},
          {"condition_number", finite_or_null(f.condition_number)},
          {"diagnostics", diagnostics}};
}

}  // namespace rrlab::storage
