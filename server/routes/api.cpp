#include <rrlab/server/routes/api.hpp>

#include <rrlab/methods/method.hpp>
#include <rrlab/scenario/scenario.hpp>
#include <rrlab/sim/run_inputs.hpp>
#include <rrlab/storage/completion.hpp>
#include <rrlab/storage/database.hpp>
#include <rrlab/util/nesting_depth.hpp>

namespace rrlab::server {

ApiResponse json_response(int status, const nlohmann::json& body) {
  ApiResponse r;
  r.status = status;
  r.body = safe_dump(body);
  return r;
}

std::string safe_dump(const nlohmann::json& body) {
  return body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

namespace {
nlohmann::json error_json(const ApiError& e) {
  nlohmann::json out = {{"code", e.code()}, {"message", e.what()}, {"path", e.path()}};
  if (e.detail().is_object())
    for (const auto& [key, value] : e.detail().items()) out.emplace(key, value);  // never over code/message/path
  return out;
}
}  // namespace

ApiResponse error_response(const ApiError& e) { return json_response(e.status(), {{"error", error_json(e)}}); }

nlohmann::json socket_error(const ApiError& e) { return {{"type", "error"}, {"error", error_json(e)}}; }

nlohmann::json socket_reply(const std::function<nlohmann::json()>& handle) {
  try {
    try {
      return {{"type", "ack"}, {"status", handle()}};
    } catch (...) {
      rethrow_as_api_error("");
    }
  } catch (const ApiError& e) {
    return socket_error(e);
  }
}

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
}  // namespace

nlohmann::json parse_client_json(const std::string& text) {
  try {
    return parse_json(text);
  } catch (const TooDeepError& e) {
    throw ApiError(400, "too_deep", e.what(), "");
  } catch (const nlohmann::json::exception& e) {
    throw ApiError(400, "malformed_json", plain_reason(e) + " at byte " + std::to_string(error_byte(text)), "");
  }
}

nlohmann::json parse_body(const ApiRequest& request) {
  if (request.body.empty()) throw ApiError(400, "malformed_json", "the request needs a JSON body", "");
  return parse_client_json(request.body);
}

namespace {
int hex(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}
std::string decode(const std::string& s) {
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '+') {
      out += ' ';
    } else if (s[i] == '%' && i + 2 < s.size() && hex(s[i + 1]) >= 0 && hex(s[i + 2]) >= 0) {
      out += char(hex(s[i + 1]) * 16 + hex(s[i + 2]));
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
}
std::string join_path(const std::string& prefix, const std::string& path) {
  if (prefix.empty()) return path;
  if (path.empty()) return prefix;
  return prefix + "." + path;
}
}  // namespace

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
    if (!pair.empty()) out[decode(pair.substr(0, eq))] = eq == std::string::npos ? "" : decode(pair.substr(eq + 1));
    start = end + 1;
  }
  return out;
}

void rethrow_as_api_error(const std::string& prefix, int validation_status) {
  try {
    throw;
  } catch (const ApiError&) {
    throw;
  } catch (const ScenarioError& e) {
    throw ApiError(validation_status, "invalid", e.what(), join_path(prefix, e.path()));
  } catch (const ParamError& e) {
    throw ApiError(400, "invalid_param", e.param() + ": " + e.what(), join_path(prefix, e.param()));
  } catch (const InputStateError& e) {
    throw ApiError(409, "wrong_state", e.what(), prefix);
  } catch (const storage::StorageError& e) {
    // a full disk or read-only file: the request may succeed later (reads still work)
    if (e.fault() == storage::StorageFault::full)
      throw ApiError(503, "storage_full", std::string("the database's disk is full: ") + e.what(), "");
    if (e.fault() == storage::StorageFault::readonly)
      throw ApiError(503, "storage_readonly", std::string("the database cannot be written: ") + e.what(), "");
    throw ApiError(500, "storage", e.what(), "");
  } catch (const std::exception& e) {
    throw ApiError(500, "internal", e.what(), "");
  }
}

nlohmann::json settled_status(const nlohmann::json& status, const storage::Outcome& outcome, const std::string& path) {
  if (outcome.ok()) return outcome.result.is_null() ? status : outcome.result;
  const std::string message = "storing the input failed: " + outcome.error;
  if (outcome.fault == storage::StorageFault::full) throw ApiError(503, "storage_full", message, path);
  if (outcome.fault == storage::StorageFault::readonly) throw ApiError(503, "storage_readonly", message, path);
  throw ApiError(500, "storage", message, path);
}

}  // namespace rrlab::server
