// A stored run as the API shows it: GET /api/runs/{id}, the run list, and
// each lane's metadata in a one-file export (app/html_export.cpp).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include <rrlab/storage/run_store.hpp>

namespace rrlab::server {

nlohmann::json run_record_json(const storage::RunRecord& run);

// A stored JSON text, parsed; null when there is none, or when it no longer
// parses (a record is shown, not refused, for one bad field).
nlohmann::json parse_or_null(const std::optional<std::string>& text);

}  // namespace rrlab::server
