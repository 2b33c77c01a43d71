// Nesting depth limits for the text documents rrlab reads (JSON: REST bodies,
// WebSocket messages, scenario files, run records, sweep specs; XML: URDF).
// Both libraries behind them recurse once per level somewhere (nlohmann's
// copy and dump, TinyXML's parser), so a deep enough document overflows the
// stack. The checks below are one linear pass with no recursion; they run
// before any parser sees the text.
#pragma once

#include <cstddef>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace rrlab {

// Real documents nest 5 (URDF) to 8 (a sweep spec) levels.
inline constexpr int kMaxJsonDepth = 64;
inline constexpr int kMaxXmlDepth = 64;

// The byte offset of the first `[` or `{` (outside strings) that opens level
// max_depth + 1, or nullopt when the text never nests that deep. Malformed
// JSON is scanned as far as it goes: the parser reports what is wrong with it.
std::optional<std::size_t> json_too_deep_at(std::string_view text, int max_depth = kMaxJsonDepth);

// The byte offset of the first start tag that opens element level
// max_depth + 1 (comments, CDATA, processing instructions, declarations and
// quoted attribute values are skipped), or nullopt.
std::optional<std::size_t> xml_too_deep_at(std::string_view text, int max_depth = kMaxXmlDepth);

// A document nested deeper than its limit. `offset` is 0-based; byte() and
// the message count from 1, as the JSON parser's "at byte N" does.
class TooDeepError : public std::runtime_error {
 public:
  TooDeepError(const std::string& what_kind, int max_depth, std::size_t offset);
  std::size_t byte() const { return byte_; }

 private:
  std::size_t byte_;
};

// nlohmann::json::parse after json_too_deep_at: throws TooDeepError for a
// document deeper than kMaxJsonDepth, else what nlohmann throws.
nlohmann::json parse_json(std::string_view text);

}  // namespace rrlab
