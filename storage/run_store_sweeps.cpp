// RunStore's sweep functions: a whole run and its sweep_runs row stored in
// one transaction (resume and merge rely on never seeing half a run).
#include <cmath>

#include <rrlab/storage/database.hpp>
#include <rrlab/storage/run_store.hpp>

namespace rrlab::storage {

std::optional<std::int64_t> RunStore::add_sweep_run(const FinishedRun& finished, const SweepRunRow& row) {
  std::optional<std::int64_t> added;
  recording_faults([&] {
  std::lock_guard lock(mutex_);
  Transaction tx(*db_);
  Statement exists = db_->prepare("SELECT 1 FROM sweep_runs WHERE sweep = ? AND key = ?");
  exists.bind(1, row.sweep).bind(2, row.key);
  if (exists.step()) return;  // rolled back: nothing was written

  const NewRun& run = finished.run;
  Statement insert_run = db_->prepare(
      "INSERT INTO runs(scenario_name, scenario, method, params, seed, mode, created, status, frames, summary, "
      "dof, diagnostic_names, source_run, compare_group, frame_bytes) "
      "VALUES (?,?,?,?,?,?,?,'completed',?,?,?,?,?,?,?)");
  insert_run.bind(1, run.scenario_name).bind(2, run.scenario_json).bind(3, run.method).bind(4, run.params_json);
  insert_run.bind(5, std::int64_t(run.seed)).bind(6, run.mode).bind(7, finished.created.value_or(utc_now()));
  insert_run.bind(8, std::int64_t(finished.frames.size())).bind(9, finished.summary_json).bind(10, run.dof);
  insert_run.bind(11, run.diagnostic_names_json);
  if (run.source_run) insert_run.bind(12, *run.source_run); else insert_run.bind_null(12);
  if (run.compare_group) insert_run.bind(13, *run.compare_group); else insert_run.bind_null(13);
  std::int64_t frame_bytes = 0;
  for (const StoredFrame& f : finished.frames) frame_bytes += std::int64_t(f.data.size());
  insert_run.bind(14, frame_bytes);
  insert_run.step();
  const std::int64_t id = db_->last_insert_id();

  if (!finished.frames.empty()) {
    Statement insert = db_->prepare(
        "INSERT INTO frames(run_id, seq, step, t, task_error, min_distance, collided, data) VALUES (?,?,?,?,?,?,?,?)");
    for (const StoredFrame& f : finished.frames) {
      insert.bind(1, id).bind(2, f.seq).bind(3, f.step).bind(4, f.t).bind(5, f.task_error);
      if (std::isfinite(f.min_distance)) insert.bind(6, f.min_distance); else insert.bind_null(6);
      insert.bind(7, f.collided ? 1 : 0).bind_blob(8, f.data);
      insert.step();
      insert.reset();
    }
  }
  if (!finished.events.empty()) {
    Statement insert = db_->prepare("INSERT INTO events(run_id, seq, step, kind, payload) VALUES (?,?,?,?,?)");
    for (const StoredEvent& e : finished.events) {
      insert.bind(1, id).bind(2, e.seq).bind(3, e.step).bind(4, e.kind).bind(5, e.payload_json);
      insert.step();
      insert.reset();
    }
  }
  Statement insert_row = db_->prepare(
      "INSERT INTO sweep_runs(sweep, key, run_id, scenario_key, config_key, family, success, failure_mode, failure_t) "
      "VALUES (?,?,?,?,?,?,?,?,?)");
  insert_row.bind(1, row.sweep).bind(2, row.key).bind(3, id).bind(4, row.scenario_key).bind(5, row.config_key);
  insert_row.bind(6, row.family).bind(7, row.success ? 1 : 0);
  if (row.failure_mode) insert_row.bind(8, *row.failure_mode); else insert_row.bind_null(8);
  if (row.failure_t) insert_row.bind(9, *row.failure_t); else insert_row.bind_null(9);
  insert_row.step();
  tx.commit();
  total_frame_bytes_ += frame_bytes;
  added = id;
  });
  return added;
}

std::vector<std::string> RunStore::sweep_keys(const std::string& sweep) {
  std::lock_guard lock(read_mutex_);
  Statement s = read_db_->prepare("SELECT key FROM sweep_runs WHERE sweep = ? ORDER BY key");
  s.bind(1, sweep);
  std::vector<std::string> out;
  while (s.step()) out.push_back(s.column_text(0));
  return out;
}

namespace {

// The columns every sweep-run read selects, in SweepRunEntry's order.
constexpr const char* kSweepRunColumns =
    "SELECT w.sweep, w.key, w.scenario_key, w.config_key, w.family, w.success, w.run_id, r.seed, r.summary, "
    "w.failure_mode, w.failure_t, json_extract(r.scenario, '$.witness.difficulty'), r.frames "
    "FROM sweep_runs w JOIN runs r ON r.id = w.run_id ";

SweepRunEntry sweep_run_entry(Statement& s) {
  SweepRunEntry e;
  e.row = {s.column_text(0), s.column_text(1), s.column_text(2), s.column_text(3), s.column_text(4),
           s.column_int(5) != 0};
  e.run_id = s.column_int(6);
  e.seed = std::uint64_t(s.column_int(7));
  if (!s.is_null(8)) e.summary_json = s.column_text(8);
  if (!s.is_null(9)) e.row.failure_mode = s.column_text(9);
  if (!s.is_null(10)) e.row.failure_t = s.column_double(10);
  if (!s.is_null(11)) e.difficulty_json = s.column_text(11);
  e.frames = s.column_int(12);
  return e;
}

// ?1 sweep, ?2 family (as reported: a file's runs by scenario key), ?3 config, ?4 success, ?5 failure mode
constexpr const char* kSweepRunFilter =
    "WHERE w.sweep = ?1 AND (?2 IS NULL OR (CASE WHEN w.family = 'file' THEN w.scenario_key ELSE w.family END) = ?2) "
    "AND (?3 IS NULL OR w.config_key = ?3) AND (?4 IS NULL OR w.success = ?4) AND (?5 IS NULL OR w.failure_mode = ?5) ";

std::vector<SweepRunEntry> entries_of(Statement& s) {
  std::vector<SweepRunEntry> out;
  while (s.step()) out.push_back(sweep_run_entry(s));
  return out;
}

void bind_filter(Statement& s, const std::string& sweep, const RunStore::SweepRunFilter& f) {
  s.bind(1, sweep);
  if (f.family) s.bind(2, *f.family); else s.bind_null(2);
  if (f.config) s.bind(3, *f.config); else s.bind_null(3);
  if (f.success) s.bind(4, std::int64_t(*f.success ? 1 : 0)); else s.bind_null(4);
  if (f.failure_mode) s.bind(5, *f.failure_mode); else s.bind_null(5);
}

}  // namespace

std::vector<SweepRunEntry> RunStore::sweep_runs(const std::optional<std::string>& sweep, const std::atomic<bool>* cancel) {
  std::lock_guard lock(read_mutex_);
  Statement s = read_db_->prepare(std::string(kSweepRunColumns) +
                                  "WHERE (?1 IS NULL OR w.sweep = ?1) ORDER BY w.sweep, w.key");
  if (sweep) s.bind(1, *sweep); else s.bind_null(1);
  std::vector<SweepRunEntry> out;
  while (s.step()) {
    if (cancel && (out.size() & 255) == 0 && cancel->load()) break;
    out.push_back(sweep_run_entry(s));
  }
  return out;
}

std::vector<SweepRunEntry> RunStore::sweep_runs_page(const std::string& sweep, const SweepRunFilter& filter,
                                                     std::int64_t limit, std::int64_t offset, std::int64_t& total) {
  std::lock_guard lock(read_mutex_);
  Statement count = read_db_->prepare(std::string("SELECT COUNT(*) FROM sweep_runs w ") + kSweepRunFilter);
  bind_filter(count, sweep, filter);
  total = count.step() ? count.column_int(0) : 0;
  Statement s = read_db_->prepare(std::string(kSweepRunColumns) + kSweepRunFilter + "ORDER BY w.key LIMIT ?6 OFFSET ?7");
  bind_filter(s, sweep, filter);
  s.bind(6, limit).bind(7, offset);
  return entries_of(s);
}

std::vector<SweepRunEntry> RunStore::sweep_runs_after(const std::string& sweep, const SweepRunFilter& filter,
                                                      const std::string& after_key, std::int64_t limit) {
  std::lock_guard lock(read_mutex_);
  Statement s = read_db_->prepare(std::string(kSweepRunColumns) + kSweepRunFilter + "AND w.key > ?6 ORDER BY w.key LIMIT ?7");
  bind_filter(s, sweep, filter);
  s.bind(6, after_key).bind(7, limit);
  return entries_of(s);
}

}  // namespace rrlab::storage
