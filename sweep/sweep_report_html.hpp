// A sweep report as one self-contained HTML page: the Markdown report's
// tables, and per sweep an inline SVG bar chart of each configuration ×
// family's success rate with its Wilson interval as an error bar. No
// scripts, no network.
#pragma once

#include <ostream>

#include <rrlab/sweep/sweep_report.hpp>

namespace rrlab::sweep {

void write_report_html(std::ostream& out, const SweepReport& report);

}  // namespace rrlab::sweep
