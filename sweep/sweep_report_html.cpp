#include <rrlab/sweep/sweep_report_html.hpp>

#include <algorithm>
#include <cstdio>
#include <span>
#include <string>

#include <rrlab/sweep/sweep_report_text.hpp>

namespace rrlab::sweep {

namespace {

std::string escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string fixed(double value) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", value);
  return buf;
}

// Horizontal bars: one row per group, 0–100 % axis, interval whiskers.
void success_chart(std::ostream& out, const SweepReport& report, const std::string& sweep) {
  constexpr double kLabel = 320, kPlot = 480, kRow = 26, kTop = 24;
  int rows = 0;
  for (const GroupStats& g : report.groups) rows += g.sweep == sweep ? 1 : 0;
  const double height = kTop + kRow * rows + 8;
  out << "<svg role=\"img\" aria-label=\"success rate by method configuration and family\" width=\""
      << fixed(kLabel + kPlot + 60) << "\" height=\"" << fixed(height) << "\" xmlns=\"http://www.w3.org/2000/svg\">\n";
  for (int tick = 0; tick <= 100; tick += 25) {
    const double x = kLabel + kPlot * tick / 100.0;
    out << "<line x1=\"" << fixed(x) << "\" y1=\"" << fixed(kTop - 4) << "\" x2=\"" << fixed(x) << "\" y2=\""
        << fixed(height - 8) << "\" stroke=\"#ddd\"/><text x=\"" << fixed(x) << "\" y=\"14\" font-size=\"11\" "
        << "text-anchor=\"middle\" fill=\"#555\">" << tick << "%</text>\n";
  }
  int row = 0;
  for (const GroupStats& g : report.groups) {
    if (g.sweep != sweep) continue;
    const double y = kTop + kRow * row++;
    const double w = kPlot * g.success_rate, lo = kLabel + kPlot * g.success_interval.low,
                 hi = kLabel + kPlot * g.success_interval.high, mid = y + kRow / 2 - 2;
    out << "<text x=\"" << fixed(kLabel - 8) << "\" y=\"" << fixed(mid + 4) << "\" font-size=\"12\" "
        << "text-anchor=\"end\">" << escape(g.config_key + " · " + g.family) << "</text>\n"
        << "<rect x=\"" << fixed(kLabel) << "\" y=\"" << fixed(y + 4) << "\" width=\"" << fixed(w) << "\" height=\""
        << fixed(kRow - 12) << "\" fill=\"#4a7fb5\"><title>" << escape(percent(g.success_rate) + " of " +
                                                                         std::to_string(g.n) + ", 95% CI " +
                                                                         percent(g.success_interval.low) + "–" +
                                                                         percent(g.success_interval.high))
        << "</title></rect>\n"
        << "<path d=\"M" << fixed(lo) << " " << fixed(mid) << "H" << fixed(hi) << "M" << fixed(lo) << " "
        << fixed(mid - 5) << "V" << fixed(mid + 5) << "M" << fixed(hi) << " " << fixed(mid - 5) << "V"
        << fixed(mid + 5) << "\" stroke=\"#222\" stroke-width=\"1.5\" fill=\"none\"/>\n"
        << "<text x=\"" << fixed(kLabel + kPlot + 6) << "\" y=\"" << fixed(mid + 4) << "\" font-size=\"11\">"
        << percent(g.success_rate) << "</text>\n";
  }
  out << "</svg>\n";
}

// One line of a success-by-bin chart: a configuration and its bins.
struct BinLine {
  const std::string* config;
  std::span<const DifficultyBin> bins;
};

// Success per bin, one line per configuration: the bins evenly spaced on x
// (their labels below, `axis` under them), success on y, a legend beside.
void bins_svg(std::ostream& out, const std::string& aria, const std::string& axis, const std::vector<std::string>& labels,
              const std::vector<BinLine>& lines) {
  static const char* kColours[] = {"#4a7fb5", "#d9822b", "#3a9d5d", "#c23b3b", "#8e6bbf", "#8c6d46",
                                   "#d46fb0", "#6f6f6f", "#b5b531", "#2fb3c4", "#1f3b73", "#e0a100"};
  constexpr double kLeft = 50, kPlot = 420, kHeight = 200, kTop = 16, kLegend = 260;
  constexpr double kGap = 70;  // between the plot and its legend: room for the last bin's label
  const double height = std::max(kHeight, 18.0 * double(lines.size())) + kTop + 46;
  const double step = labels.size() > 1 ? kPlot / double(labels.size() - 1) : 0;
  out << "<svg role=\"img\" aria-label=\"" << escape(aria) << "\" width=\"" << fixed(kLeft + kPlot + kGap + kLegend)
      << "\" height=\"" << fixed(height) << "\" xmlns=\"http://www.w3.org/2000/svg\">\n";
  const auto y_of = [&](double rate) { return kTop + kHeight * (1 - rate); };
  for (int tick = 0; tick <= 100; tick += 25)
    out << "<line x1=\"" << fixed(kLeft) << "\" x2=\"" << fixed(kLeft + kPlot) << "\" y1=\"" << fixed(y_of(tick / 100.0))
        << "\" y2=\"" << fixed(y_of(tick / 100.0)) << "\" stroke=\"#ddd\"/><text x=\"" << fixed(kLeft - 6) << "\" y=\""
        << fixed(y_of(tick / 100.0) + 4) << "\" font-size=\"11\" text-anchor=\"end\" fill=\"#555\">" << tick << "%</text>\n";
  for (size_t k = 0; k < labels.size(); ++k)
    out << "<text x=\"" << fixed(kLeft + step * double(k)) << "\" y=\"" << fixed(kTop + kHeight + 16)
        << "\" font-size=\"11\" text-anchor=\"middle\" fill=\"#555\">" << escape(labels[k]) << "</text>\n";
  out << "<text x=\"" << fixed(kLeft + kPlot / 2) << "\" y=\"" << fixed(kTop + kHeight + 34)
      << "\" font-size=\"11\" text-anchor=\"middle\" fill=\"#555\">" << escape(axis) << "</text>\n";
  for (size_t i = 0; i < lines.size(); ++i) {
    const char* colour = kColours[i % (sizeof kColours / sizeof kColours[0])];
    std::string path;
    for (size_t k = 0; k < lines[i].bins.size(); ++k) {
      const DifficultyBin& b = lines[i].bins[k];
      if (b.n == 0) continue;
      path += (path.empty() ? "M" : "L") + fixed(kLeft + step * double(k)) + " " + fixed(y_of(double(b.successes) / double(b.n)));
    }
    out << "<path d=\"" << path << "\" stroke=\"" << colour << "\" stroke-width=\"2\" fill=\"none\"/>\n";
    for (size_t k = 0; k < lines[i].bins.size(); ++k) {
      const DifficultyBin& b = lines[i].bins[k];
      if (b.n == 0) continue;
      out << "<circle cx=\"" << fixed(kLeft + step * double(k)) << "\" cy=\"" << fixed(y_of(double(b.successes) / double(b.n)))
          << "\" r=\"3\" fill=\"" << colour << "\"><title>" << escape(*lines[i].config) << ": " << b.successes << " of "
          << b.n << "</title></circle>\n";
    }
    out << "<rect x=\"" << fixed(kLeft + kPlot + kGap) << "\" y=\"" << fixed(kTop + 18.0 * double(i)) << "\" width=\"12\" height=\"3\" fill=\""
        << colour << "\"/><text x=\"" << fixed(kLeft + kPlot + kGap + 18) << "\" y=\"" << fixed(kTop + 18.0 * double(i) + 5)
        << "\" font-size=\"12\">" << escape(*lines[i].config) << "</text>\n";
  }
  out << "</svg>\n";
}

// Success against difficulty, one chart per family: the family's bins (the
// quartiles of its cases' witness clearance or limit margin) on x, harder
// (smaller) first, success on y, one line per configuration.
void difficulty_charts(std::ostream& out, const SweepReport& report, const std::string& sweep) {
  std::vector<std::string> families;
  for (const GroupStats& g : report.groups)
    if (g.sweep == sweep && !g.by_difficulty.empty() && std::find(families.begin(), families.end(), g.family) == families.end())
      families.push_back(g.family);
  if (families.empty()) return;
  out << "<h3>Success against difficulty</h3>\n<p class=\"note\">Each family's cases in four bins at the quartiles "
         "of the witness's clearance from the obstacles (or, without obstacles, its joint-limit margin): the "
         "narrowest cases on the left. Success per bin for every configuration (hover a point for its count).</p>\n";
  for (const std::string& family : families) {
    std::vector<BinLine> lines;
    const GroupStats* first = nullptr;  // the family's bins and measure (every configuration's are the same)
    for (const GroupStats& g : report.groups)
      if (g.sweep == sweep && g.family == family && !g.by_difficulty.empty()) {
        if (!first) first = &g;
        lines.push_back({&g.config_key, g.by_difficulty});
      }
    std::vector<std::string> labels;
    for (const DifficultyBin& b : first->by_difficulty) labels.push_back(short_number(b.low) + "–" + short_number(b.high));
    const std::string& measure = first->difficulty_measure;
    out << "<h4>" << escape(family) << " (" << escape(measure) << ")</h4>\n";
    bins_svg(out, "success against " + measure + " in " + family, measure + (measure == "clearance" ? " (m)" : " (rad)"),
             labels, lines);
  }
}

// Success against the obstacle counts: one chart per family and count, the
// bins 0 .. 4+ on x (more obstacles, harder, to the right).
void count_charts(std::ostream& out, const SweepReport& report, const std::string& sweep) {
  const std::vector<CountRow> rows = count_rows(report, sweep);
  if (rows.empty()) return;
  out << "<h3>Success against obstacle counts</h3>\n<p class=\"note\">" << escape(count_rule_text()) << "</p>\n";
  for (size_t begin = 0; begin < rows.size();) {
    size_t end = begin;
    std::vector<BinLine> lines;
    for (; end < rows.size() && rows[end].family == rows[begin].family && rows[end].measure == rows[begin].measure; ++end) {
      const GroupStats& g = report.groups[rows[end].group];
      lines.push_back({&g.config_key, g.by_count[rows[end].measure].bins});
    }
    const CountDifficulty& first = report.groups[rows[begin].group].by_count[rows[begin].measure];
    std::vector<std::string> labels;
    for (const DifficultyBin& b : first.bins) labels.push_back(count_bin_label(b));
    const std::string& family = rows[begin].family;
    out << "<h4>" << escape(family) << " (" << first.measure << ")</h4>\n";
    bins_svg(out, "success against " + first.measure + " in " + family, first.measure + " (count)", labels, lines);
    begin = end;
  }
}

// What to try when the first choice fails: the pair per family, then each
// family's unsolved cases with the commands that write them.
void fallbacks_html(std::ostream& out, const SweepReport& report, const std::string& sweep) {
  out << "<h3>What to try when the first choice fails</h3>\n<p class=\"note\">" << escape(fallback_rule_text())
      << "</p>\n<table><tr><th>family</th><th>first choice, then fallback (solved/cases)</th><th>cost µs/step</th>"
         "<th>solved by some configuration</th><th>unsolved</th></tr>\n";
  for (const FamilyFallback& f : report.fallbacks) {
    if (f.sweep != sweep) continue;
    out << "<tr><td>" << escape(f.family) << "</td><td>" << escape(fallback_choice_text(f)) << "</td><td class=\"n\">"
        << short_number(f.cost_us) << "</td><td class=\"n\">" << f.solved_by_some << "/" << f.cases
        << "</td><td class=\"n\">" << f.unsolved << "</td></tr>\n";
  }
  out << "</table>\n";
  for (const FamilyFallback& f : report.fallbacks) {
    if (f.sweep != sweep || f.unsolved == 0) continue;
    out << "<p><b>" << escape(f.family) << "</b>, unsolved: " << escape(unsolved_text(f)) << "</p>\n";
    for (const std::string& command : unsolved_commands(f)) out << "<pre>" << escape(command) << "</pre>\n";
  }
}

}  // namespace

void write_report_html(std::ostream& out, const SweepReport& report) {
  out << "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>rrlab sweep report</title>\n"
      << "<style>body{font:14px/1.4 system-ui,sans-serif;margin:2em;color:#222}table{border-collapse:collapse;"
         "margin:1em 0}th,td{border:1px solid #ccc;padding:3px 8px}td.n{text-align:right}th{background:#f3f3f3}"
         "p.note{color:#555;max-width:60em}</style></head><body>\n<h1>Sweep report</h1>\n"
      << "<p class=\"note\">Success as judged by each sweep's criteria when the run was stored; bars show the success "
         "rate, whiskers its 95 % Wilson score interval. Min distance over runs with obstacles (p10: 10th "
         "percentile). Step time: median over runs of each run's step_us.p50 and of each run's step_us.p99 (wall "
         "clock, µs). Jerk: median over runs of each run's RMS joint jerk (rad/s³; the Euclidean norm over "
         "joints of q's third difference / dt³). Steps past limits: steps whose integrated q ended past a joint "
         "position limit / whose applied velocity exceeded a velocity limit, summed over the runs (— where the runs' "
         "summaries predate the count, or have no velocity limits). Paired comparisons count A's wins/losses/ties against B on the "
         "same cases (scenario and seed): on success, and on min distance (larger wins, ties within 1e-9).</p>\n";
  if (report.sweeps.empty()) out << "<p>No sweep runs stored.</p>\n";
  for (const std::string& sweep : report.sweeps) {
    out << "<h2>" << escape(sweep) << "</h2>\n";
    success_chart(out, report, sweep);
    out << "<table><tr><th>method config</th><th>family</th><th>n</th><th>success</th><th>95% CI</th>"
           "<th>min dist median</th><th>min dist p10</th><th>max track err median</th><th>joint-limit viol.</th>"
           "<th>steps past limits q / q̇</th><th>non-finite</th><th>jerk RMS median</th><th>step µs p50</th><th>step µs p99</th><th>step × pinv</th>"
           "<th>first failures</th></tr>\n";
    for (const GroupStats& g : report.groups) {
      if (g.sweep != sweep) continue;
      out << "<tr><td>" << escape(g.config_key) << "</td><td>" << escape(g.family) << "</td><td class=\"n\">" << g.n
          << "</td><td class=\"n\">" << percent(g.success_rate) << "</td><td>" << percent(g.success_interval.low)
          << "–" << percent(g.success_interval.high) << "</td><td class=\"n\">" << short_number(g.median_min_distance)
          << "</td><td class=\"n\">" << short_number(g.p10_min_distance) << "</td><td class=\"n\">"
          << short_number(g.median_max_tracking_error) << "</td><td class=\"n\">" << percent(g.joint_limit_share)
          << "</td><td class=\"n\">" << limit_steps_text(g) << "</td><td class=\"n\">" << percent(g.nonfinite_share) << "</td><td class=\"n\">"
          << short_number(g.median_rms_jerk) << "</td><td class=\"n\">"
          << short_number(g.step_us_p50) << "</td><td class=\"n\">" << short_number(g.step_us_p99)
          << "</td><td class=\"n\">" << short_number(g.step_ratio_to_pinv) << "</td><td>"
          << escape(failure_modes_text(g)) << "</td></tr>\n";
    }
    out << "</table>\n";
    difficulty_charts(out, report, sweep);
    count_charts(out, report, sweep);
    out << "<h3>Which method when</h3>\n<p class=\"note\">" << escape(verdict_rule_text())
        << "</p>\n<table><tr><th>family</th><th>cases</th><th>detects</th>"
           "<th>configurations (success, step µs p50, × pinv)</th></tr>\n";
    for (const FamilyVerdict& v : report.verdicts) {
      if (v.sweep != sweep) continue;
      out << "<tr><td>" << escape(v.family) << "</td><td class=\"n\">" << v.cases << "</td><td>"
          << escape(detectable_text(v)) << "</td><td>" << escape(verdict_text(report, v)) << "</td></tr>\n";
    }
    out << "</table>\n";
    fallbacks_html(out, report, sweep);
    out << "<h3>Against pinv and the family's best</h3>\n<table><tr><th>family</th><th>method config</th>"
           "<th>against</th><th>cases</th><th>success W/L/T</th><th>McNemar p</th></tr>\n";
    for (const FamilyComparison& c : report.comparisons) {
      if (c.sweep != sweep) continue;
      out << "<tr><td>" << escape(c.family) << "</td><td>" << escape(c.config_key) << "</td><td>" << c.role << " ("
          << escape(c.reference) << ")</td><td class=\"n\">" << c.cases << "</td><td>" << c.success.wins << "/"
          << c.success.losses << "/" << c.success.ties << "</td><td class=\"n\">" << p_value(c.mcnemar_p)
          << "</td></tr>\n";
    }
    out << "</table>\n<h3>Ranking</h3>\n<table><tr><th>rank</th><th>method config</th><th>n</th><th>success</th>"
           "<th>max track err median</th></tr>\n";
    int rank = 0;
    for (const RankEntry& r : report.ranking) {
      if (r.sweep != sweep) continue;
      out << "<tr><td class=\"n\">" << ++rank << "</td><td>" << escape(r.config_key) << "</td><td class=\"n\">" << r.n
          << "</td><td class=\"n\">" << percent(r.success_rate) << "</td><td class=\"n\">"
          << short_number(r.median_max_tracking_error) << "</td></tr>\n";
    }
    out << "</table>\n<h3>Paired comparisons</h3>\n";
    if (const std::string omitted = pairs_omitted_text(report, sweep); !omitted.empty()) {
      out << "<p>" << escape(omitted) << "</p>\n";
      continue;
    }
    out << "<table><tr><th>A</th><th>B</th><th>cases</th><th>success W/L/T</th><th>min distance W/L/T</th></tr>\n";
    for (const PairedComparison& p : report.pairs) {
      if (p.sweep != sweep) continue;
      out << "<tr><td>" << escape(p.a) << "</td><td>" << escape(p.b) << "</td><td class=\"n\">" << p.cases
          << "</td><td>" << p.success.wins << "/" << p.success.losses << "/" << p.success.ties << "</td><td>"
          << p.min_distance.wins << "/" << p.min_distance.losses << "/" << p.min_distance.ties << "</td></tr>\n";
    }
    out << "</table>\n";
  }
  out << "</body></html>\n";
}

}  // namespace rrlab::sweep
