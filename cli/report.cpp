// rrlab report DB [--sweep NAME] --format md|html|csv [--out FILE].
#include <filesystem>
#include <fstream>
#include <iostream>

#include <rrlab/storage/run_store.hpp>
#include <rrlab/sweep/sweep_report.hpp>
#include <rrlab/sweep/sweep_report_html.hpp>
#include <rrlab/sweep/sweep_report_text.hpp>

#include "cli.hpp"

namespace rrlab::cli {

int report(const ReportOptions& options) {
  try {
    if (!database_exists(options.db)) return 2;
    storage::RunStore store(options.db);
    const std::vector<storage::SweepRunEntry> runs = store.sweep_runs(options.sweep);
    if (options.sweep && runs.empty()) {
      std::cerr << "rrlab: error: --sweep: no sweep '" << *options.sweep << "' in " << options.db << '\n';
      return 2;
    }
    const sweep::SweepReport report = sweep::build_report(runs);
    std::ofstream file;
    if (options.out) {
      file.open(*options.out);
      if (!file) {
        std::cerr << "rrlab: error: --out: cannot write '" << *options.out << "'\n";
        return 2;
      }
    }
    std::ostream& out = options.out ? static_cast<std::ostream&>(file) : std::cout;
    if (options.format == "html") sweep::write_report_html(out, report);
    else if (options.format == "csv") sweep::write_report_csv(out, report);
    else sweep::write_report_markdown(out, report);
    out.flush();
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "rrlab: error: " << e.what() << '\n';
    return 2;
  }
}

}  // namespace rrlab::cli
