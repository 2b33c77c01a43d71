// A sweep report as JSON (the REST answer of a finished sweep): the same
// numbers as the md/html/csv writers; NaN (no run with a finite distance) as null.
#pragma once

#include <nlohmann/json.hpp>

#include "sweep/sweep_report.hpp"

namespace rrlab::sweep {

nlohmann::json report_json(const SweepReport& report);

}  // namespace rrlab::sweep
