#include <rrlab/server/api/request.hpp>

#include <rrlab/server/api/errors.hpp>
#include <rrlab/util/nesting_depth.hpp>

namespace rrlab::server {

namespace {
// Finds where the parser gave up: a second, SAX-only pass that keeps nothing
// but the byte offset of the first error (the DOM parser's out_of_range error
// for a number beyond double's range carries no position).
class ErrorLocator : public nlohmann::json_sax<nlohmann::json> {
 public:
  std::size_t byte = 0;
  bool null() override { return true; }
  bool boolean(bool) override { return true; }
  bool number_integer(number_integer_t) override { return true; }
  bool number_unsigned(number_unsigned_t) override { return true; }
  bool number_float(number_float_t, const string_t&) override { return true; }
  bool string(string_t&) override { return true; }
  bool binary(binary_t&) override { return true; }
  bool start_object(std::size_t) override { return true; }
  bool key(string_t&) override { return true; }
  bool end_object() override { return true; }
  bool start_array(std::size_t) override { return true; }
  bool end_array() override { return true; }
  bool parse_error(std::size_t position, const std::string&, const nlohmann::json::exception&) override {
    byte = position;
    return false;
  }
};

std::size_t error_byte(const std::string& text) {
  ErrorLocator locator;
  nlohmann::json::sax_parse(text, &locator);
  return locator.byte;
}

// The reason without the library's "[json.exception...] parse error at line
// 1, column 5: " prefix: what was wrong, in words.
std::string plain_reason(const nlohmann::json::exception& e) {
  if (e.id == 406) return "number out of range";  // out_of_range: a number beyond double
  if (e.id == 101) {                              // syntax error: keep the lexer's reason
    const std::string what = e.what();
    const auto reason = what.find(": ", what.find("column"));
    if (reason != std::string::npos) return what.substr(reason + 2);
  }
  return "invalid JSON";
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

std::string percent_decode(const std::string& s) {
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '+') {
      out += ' ';
    } else if (s[i] == '%' && i + 2 < s.size() && hex_digit(s[i + 1]) >= 0 && hex_digit(s[i + 2]) >= 0) {
      out += char(hex_digit(s[i + 1]) * 16 + hex_digit(s[i + 2]));
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
}
}  // namespace

nlohmann::json parse_client_json(const std::string& text) {
  try {
    return parse_json(text);
  } catch (const TooDeepError& e) {
    throw DomainError(Problem::invalid, "too_deep", e.what());
  } catch (const nlohmann::json::exception& e) {
    throw DomainError(Problem::invalid, "malformed_json",
                      plain_reason(e) + " at byte " + std::to_string(error_byte(text)));
  }
}

nlohmann::json parse_body(const ApiRequest& request) {
  if (request.body.empty()) throw DomainError(Problem::invalid, "malformed_json", "the request needs a JSON body");
  return parse_client_json(request.body);
}

std::optional<std::int64_t> parse_id(std::string_view text) {
  if (text.empty() || text.size() > 18) return std::nullopt;
  std::int64_t value = 0;
  for (char c : text) {
    if (c < '0' || c > '9') return std::nullopt;
    value = value * 10 + (c - '0');
  }
  return value;
}

std::map<std::string, std::string> parse_query(const std::string& query) {
  std::map<std::string, std::string> out;
  size_t start = 0;
  while (start < query.size()) {
    size_t end = query.find('&', start);
    if (end == std::string::npos) end = query.size();
    const std::string pair = query.substr(start, end - start);
    const size_t eq = pair.find('=');
    if (!pair.empty())
      out[percent_decode(pair.substr(0, eq))] = eq == std::string::npos ? "" : percent_decode(pair.substr(eq + 1));
    start = end + 1;
  }
  return out;
}

}  // namespace rrlab::server
