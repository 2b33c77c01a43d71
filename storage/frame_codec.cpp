#include "storage/frame_codec.hpp"

#include <bit>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "sim/frame_json.hpp"
#include "util/number_text.hpp"

namespace rrlab::storage {

static_assert(std::endian::native == std::endian::little, "the frame blob is little-endian");

namespace {

// Bytes of the blob after its two counts: the step (i64) and the doubles of
// every other blob field, in kFrameFields order.
size_t blob_body_size(std::uint32_t n, std::uint32_t k) {
  size_t bytes = 0;
  for (const FrameField& field : kFrameFields)
    if (field.outputs & kFrameBlob) bytes += 8 * size_t(frame_value_count(field.kind, int(n), int(k)));
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
void pack_field(const Frame& f, char*& at) {
  constexpr const FrameField& field = kFrameFields[I];
  if constexpr ((field.outputs & kFrameBlob) != 0) {
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
void unpack_field(Frame& f, const char*& at, std::uint32_t n, std::uint32_t k) {
  constexpr const FrameField& field = kFrameFields[I];
  if constexpr ((field.outputs & kFrameBlob) != 0) {
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
void pack_fields(const Frame& f, char* at, std::index_sequence<I...>) {
  (pack_field<I>(f, at), ...);
}

template <size_t... I>
void unpack_fields(Frame& f, const char* at, std::uint32_t n, std::uint32_t k, std::index_sequence<I...>) {
  (unpack_field<I>(f, at, n, k), ...);
}

constexpr auto kFieldIndices = std::make_index_sequence<kFrameFields.size()>();

}  // namespace

void pack_frame(const Frame& f, std::string& out) {
  const auto n = std::uint32_t(f.q.size()), k = std::uint32_t(f.diagnostics.size());
  out.resize(8 + blob_body_size(n, k));
  pack_fields(f, put(put(out.data(), n), k), kFieldIndices);
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
  if (n > 4096 || k > 4096 || in.size() != blob_body_size(n, k))
    throw std::runtime_error("frame blob has the wrong size");
  Frame f;
  f.q.resize(n);
  f.qdot.resize(n);
  f.diagnostics.resize(k);
  unpack_fields(f, in.data(), n, k, kFieldIndices);
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
