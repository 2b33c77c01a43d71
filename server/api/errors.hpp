// The server's domain errors: what went wrong, in the app's words. The app
// layer (server/app/) throws DomainError; the routes (server/routes/) give
// each Problem its HTTP status in one table (routes/http_errors.hpp) and
// answer {"error": {"code", "message", "path", ...detail}}.
#pragma once

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

namespace rrlab::storage {
struct Outcome;
}

namespace rrlab::server {

// What kind of refusal an error is; the HTTP status follows from it alone.
enum class Problem {
  invalid,           // a request that is malformed or out of range
  unauthorized,      // a watch-only connection that tries to steer
  not_found,         // no such run, replay, sweep, scenario or route
  not_allowed,       // a route that does not take this verb
  conflict,          // the wrong state (a live run, a replay playing), a name taken, another controller
  too_large,         // a run beyond a per-run limit (frames, bytes, cost)
  unprocessable,     // a well-formed document the engine refuses (a scenario, a sweep spec)
  too_many,          // beyond a per-client count (live runs, replays, messages, attempts)
  busy,              // every slot in use, or the server is stopping: try again later
  unavailable,       // the resource cannot take this now (a run whose frames could not be stored)
  storage_full,      // the database's disk is full (reads still work)
  storage_readonly,  // the database cannot be written (reads still work)
  quota,             // beyond a total the server keeps (bytes, scenarios)
  storage,           // the database failed
  internal,          // anything unexpected
};

// A refusal with its machine-readable code (the REST contract's "code":
// "wrong_state", "run_too_large", ...), its message, the JSON path of the
// field it concerns ("" if none) and extra members for the error object (a
// refused limit: {"limit", "requested", "allowed", ...}).
class DomainError : public std::runtime_error {
 public:
  DomainError(Problem problem, std::string code, const std::string& message, std::string path = "",
              nlohmann::json detail = nullptr)
      : std::runtime_error(message),
        problem_(problem),
        code_(std::move(code)),
        path_(std::move(path)),
        detail_(std::move(detail)) {}
  Problem problem() const { return problem_; }
  const std::string& code() const { return code_; }
  const std::string& path() const { return path_; }
  const nlohmann::json& detail() const { return detail_; }
  // The same error with its path under `prefix` ("payload" and "id": "payload.id"; "" stays "payload").
  DomainError under(const std::string& prefix) const;

 private:
  Problem problem_;
  std::string code_, path_;
  nlohmann::json detail_;
};

// "prefix.path", or whichever of the two is not empty.
std::string join_path(const std::string& prefix, const std::string& path);

// Rethrows the exception being handled as a DomainError: engine errors
// (ScenarioError: `validation`, "invalid"; ParamError: invalid
// "invalid_param"; InputStateError: conflict "wrong_state") with their JSON
// paths under `prefix`, storage errors (storage_full, storage_readonly,
// storage), anything else internal. A DomainError passes unchanged.
[[noreturn]] void rethrow_as_domain_error(const std::string& prefix, Problem validation = Problem::invalid);

// The status to answer once queued work has settled (storage/completion.hpp):
// the work's own result if it has one, else `status`. Input that could not be
// stored throws storage_full or storage_readonly (the condition may pass),
// else storage.
nlohmann::json settled_status(const nlohmann::json& status, const storage::Outcome& outcome, const std::string& path);

}  // namespace rrlab::server
