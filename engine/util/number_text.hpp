// Doubles as text for the hand-written JSON and CSV writers (frames are
// written too often for a DOM): std::to_chars, no locale, no allocation.
#pragma once

#include <charconv>
#include <cmath>
#include <string>

namespace rrlab {

// digits 0: the shortest text that reads back to the same double; otherwise
// that many significant digits. `value` must be finite.
inline void append_number(double value, int digits, std::string& out) {
  char buf[32];
  const auto r = digits > 0 ? std::to_chars(buf, buf + sizeof buf, value, std::chars_format::general, digits)
                            : std::to_chars(buf, buf + sizeof buf, value);
  out.append(buf, size_t(r.ptr - buf));
}

// JSON has no inf or NaN: they are written as null.
inline void append_json_number(double value, int digits, std::string& out) {
  if (std::isfinite(value))
    append_number(value, digits, out);
  else
    out += "null";
}

inline void append_integer(long long value, std::string& out) {
  char buf[24];
  const auto r = std::to_chars(buf, buf + sizeof buf, value);
  out.append(buf, size_t(r.ptr - buf));
}

}  // namespace rrlab
