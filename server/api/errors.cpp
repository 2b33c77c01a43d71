#include <rrlab/server/api/errors.hpp>

#include <rrlab/methods/method.hpp>
#include <rrlab/scenario/scenario.hpp>
#include <rrlab/sim/run_inputs.hpp>
#include <rrlab/storage/completion.hpp>
#include <rrlab/storage/database.hpp>

namespace rrlab::server {

std::string join_path(const std::string& prefix, const std::string& path) {
  if (prefix.empty()) return path;
  if (path.empty()) return prefix;
  return prefix + "." + path;
}

DomainError DomainError::under(const std::string& prefix) const {
  return DomainError(problem_, code_, what(), join_path(prefix, path_), detail_);
}

void rethrow_as_domain_error(const std::string& prefix, Problem validation) {
  try {
    throw;
  } catch (const DomainError&) {
    throw;
  } catch (const ScenarioError& e) {
    throw DomainError(validation, "invalid", e.what(), join_path(prefix, e.path()));
  } catch (const ParamError& e) {
    throw DomainError(Problem::invalid, "invalid_param", e.param() + ": " + e.what(), join_path(prefix, e.param()));
  } catch (const InputStateError& e) {
    throw DomainError(Problem::conflict, "wrong_state", e.what(), prefix);
  } catch (const storage::StorageError& e) {
    // a full disk or read-only file: the request may succeed later (reads still work)
    if (e.fault() == storage::StorageFault::full)
      throw DomainError(Problem::storage_full, "storage_full", std::string("the database's disk is full: ") + e.what());
    if (e.fault() == storage::StorageFault::readonly)
      throw DomainError(Problem::storage_readonly, "storage_readonly",
                        std::string("the database cannot be written: ") + e.what());
    throw DomainError(Problem::storage, "storage", e.what());
  } catch (const std::exception& e) {
    throw DomainError(Problem::internal, "internal", e.what());
  }
}

nlohmann::json settled_status(const nlohmann::json& status, const storage::Outcome& outcome, const std::string& path) {
  if (outcome.ok()) return outcome.result.is_null() ? status : outcome.result;
  const std::string message = "storing the input failed: " + outcome.error;
  if (outcome.fault == storage::StorageFault::full) throw DomainError(Problem::storage_full, "storage_full", message, path);
  if (outcome.fault == storage::StorageFault::readonly)
    throw DomainError(Problem::storage_readonly, "storage_readonly", message, path);
  throw DomainError(Problem::storage, "storage", message, path);
}

}  // namespace rrlab::server
