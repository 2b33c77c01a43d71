#include <rrlab/util/nesting_depth.hpp>

#include <nlohmann/json.hpp>

namespace rrlab {

std::optional<std::size_t> json_too_deep_at(std::string_view text, int max_depth) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') {
        ++i;  // the escaped character, `"` included
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth) return i;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return std::nullopt;
}

namespace {
// Index just past `end` at or after `from`, or text.size() when it is missing.
std::size_t past(std::string_view text, std::size_t from, std::string_view end) {
  const std::size_t at = text.find(end, from);
  return at == std::string_view::npos ? text.size() : at + end.size();
}
}  // namespace

std::optional<std::size_t> xml_too_deep_at(std::string_view text, int max_depth) {
  int depth = 0;
  std::size_t i = 0;
  while ((i = text.find('<', i)) != std::string_view::npos) {
    const std::size_t tag = i;
    const std::string_view rest = text.substr(i);
    if (rest.substr(0, 4) == "<!--") {
      i = past(text, i + 4, "-->");
    } else if (rest.substr(0, 9) == "<![CDATA[") {
      i = past(text, i + 9, "]]>");
    } else if (rest.substr(0, 2) == "<?") {
      i = past(text, i + 2, "?>");
    } else if (rest.substr(0, 2) == "<!") {  // <!DOCTYPE …>: its internal subset holds no elements
      i = past(text, i + 2, ">");
    } else if (rest.substr(0, 2) == "</") {
      i = past(text, i + 2, ">");
      if (depth > 0) --depth;
    } else {
      // A start tag: to its `>`, over quoted attribute values (which may hold `>`).
      char quote = 0;
      std::size_t j = i + 1;
      for (; j < text.size(); ++j) {
        const char c = text[j];
        if (quote) {
          if (c == quote) quote = 0;
        } else if (c == '"' || c == '\'') {
          quote = c;
        } else if (c == '>') {
          break;
        }
      }
      const bool empty_element = j < text.size() && text[j - 1] == '/';
      if (!empty_element && ++depth > max_depth) return tag;
      i = j < text.size() ? j + 1 : text.size();
    }
  }
  return std::nullopt;
}

TooDeepError::TooDeepError(const std::string& what_kind, int max_depth, std::size_t offset)
    : std::runtime_error(what_kind + " nested deeper than " + std::to_string(max_depth) + " levels at byte " +
                         std::to_string(offset + 1)),
      byte_(offset + 1) {}

nlohmann::json parse_json(std::string_view text) {
  if (const auto byte = json_too_deep_at(text)) throw TooDeepError("JSON", kMaxJsonDepth, *byte);
  return nlohmann::json::parse(text);
}

}  // namespace rrlab
