#include <rrlab/storage/frame_codec.hpp>

#include <bit>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include <rrlab/sim/frame_json.hpp>
#include <rrlab/util/number_text.hpp>

namespace rrlab::storage {

static_assert(std::endian::native == std::endian::little, "the frame blob is little-endian");

namespace {

// The first word of a versioned blob: "RF" and the version. A version-1 blob
// starts with its joint count (at most 4096), never with this.
constexpr std::uint32_t kVersionMagic = 0x52460000u;
constexpr std::uint32_t kMaxCount = 4096;

constexpr bool in_blob(const FrameField& field, int version) {
  return (field.outputs & kFrameBlob) != 0 && field.since >= 1 && field.since <= version;
}

// Bytes of the blob after its header: the step (i64) and the doubles of
// every blob field of `version`, in kFrameFields order.
size_t blob_body_size(std::uint32_t n, std::uint32_t k, int version) {
  size_t bytes = 0;
  for (const FrameField& field : kFrameFields)
    if (in_blob(field, version)) bytes += 8 * size_t(frame_value_count(field.kind, int(n), int(k)));
  return bytes;
}

template <typename T>
char* put(char* at, T value) {
  std::memcpy(at, &value, sizeof(T));
  return at + sizeof(T);
}

template <typename T>
T take(std::string_view& in) {
  if (in.size() < sizeof(T)) throw std::runtime_error("frame blob too short");
  T value;
  std::memcpy(&value, in.data(), sizeof(T));
  in.remove_prefix(sizeof(T));
  return value;
}

// The table is walked at compile time (one instance per field), so that each
// field's kind, size and place in the Frame are constants: as fast as the
// hand-written codec this replaced.
template <size_t I>
void pack_field(const Frame& f, char*& at, int version) {
  constexpr const FrameField& field = kFrameFields[I];
  if constexpr ((field.outputs & kFrameBlob) != 0) {
    if (!in_blob(field, version)) return;
    if constexpr (field.kind == FrameFieldKind::count) {
      at = put(at, std::int64_t(f.step));
    } else {
      std::array<double, 4> scratch;
      const std::span<const double> values = frame_values(f, field.id, scratch);
      if (values.empty()) return;  // no joints or no diagnostics: data() may be null, not for memcpy
      std::memcpy(at, values.data(), values.size_bytes());
      at += values.size_bytes();
    }
  }
}

// `at` has the field's bytes: unpack_frame checked the blob's size first.
template <size_t I>
void unpack_field(Frame& f, const char*& at, std::uint32_t n, std::uint32_t k, int version) {
  constexpr const FrameField& field = kFrameFields[I];
  if constexpr ((field.outputs & kFrameBlob) != 0) {
    if (!in_blob(field, version)) return;
    std::array<double, 4> scratch;
    if constexpr (field.kind == FrameFieldKind::count) {
      std::int64_t value;
      std::memcpy(&value, at, 8);
      scratch[0] = double(value);
      set_frame_values(f, field.id, {scratch.data(), 1});  // checks the range
      at += 8;
    } else {
      const size_t count = size_t(frame_value_count(field.kind, int(n), int(k)));
      if (count == 0) return;  // an empty vector's data() may be null, not for memcpy
      if (double* storage = frame_storage(f, field.id)) {
        std::memcpy(storage, at, 8 * count);
      } else {
        std::memcpy(scratch.data(), at, 8 * count);
        set_frame_values(f, field.id, {scratch.data(), count});  // checks links
      }
      at += 8 * count;
    }
  }
}

template <size_t... I>
void pack_fields(const Frame& f, char* at, int version, std::index_sequence<I...>) {
  (pack_field<I>(f, at, version), ...);
}

template <size_t... I>
void unpack_fields(Frame& f, const char* at, std::uint32_t n, std::uint32_t k, int version,
                   std::index_sequence<I...>) {
  (unpack_field<I>(f, at, n, k, version), ...);
}

constexpr auto kFieldIndices = std::make_index_sequence<kFrameFields.size()>();

}  // namespace

void pack_frame(const Frame& f, std::string& out, int version) {
  if (version < 1 || version > kFrameBlobVersion)
    throw std::invalid_argument("no frame blob version " + std::to_string(version));
  const auto n = std::uint32_t(f.q.size()), k = std::uint32_t(f.diagnostics.size());
  const size_t header = version >= 2 ? 12 : 8;
  out.resize(header + blob_body_size(n, k, version));
  char* at = out.data();
  if (version >= 2) at = put(at, kVersionMagic | std::uint32_t(version));
  pack_fields(f, put(put(at, n), k), version, kFieldIndices);
}

std::string pack_frame(const Frame& frame) {
  std::string out;
  pack_frame(frame, out);
  return out;
}

int frame_blob_version(std::string_view blob) {
  const auto first = take<std::uint32_t>(blob);
  if (first <= kMaxCount) return 1;
  if ((first & 0xffff0000u) != kVersionMagic) throw std::runtime_error("frame blob has no known header");
  const auto version = int(first & 0xffffu);
  if (version < 2 || version > kFrameBlobVersion)
    throw std::runtime_error("frame blob of version " + std::to_string(version) + ": this build reads versions 1 to " +
                             std::to_string(kFrameBlobVersion));
  return version;
}

StoredFrame stored_frame(std::int64_t seq, const Frame& f, std::string packed) {
  return {seq, f.step, f.t, f.task_error, f.min_distance, f.collided, std::move(packed)};
}

Frame unpack_frame(std::string_view in) {
  const int version = frame_blob_version(in);
  if (version >= 2) in.remove_prefix(4);
  const auto n = take<std::uint32_t>(in), k = take<std::uint32_t>(in);
  if (n > kMaxCount || k > kMaxCount || in.size() != blob_body_size(n, k, version))
    throw std::runtime_error("frame blob has the wrong size");
  Frame f;
  f.q.resize(n);
  f.qdot.resize(n);
  f.diagnostics.resize(k);
  // a blob from before self-collision knows no self distance: null, not 0
  if (version < 3) f.min_self_distance = std::numeric_limits<double>::quiet_NaN();
  unpack_fields(f, in.data(), n, k, version, kFieldIndices);
  return f;
}

void append_stored_frame_json(std::int64_t seq, const Frame& frame, std::string& out) {
  out += "{\"seq\":";
  append_integer(seq, out);
  out += ',';
  append_frame_json_members(frame, FrameOrigin::stored, 0, out);
  out += '}';
}

}  // namespace rrlab::storage
