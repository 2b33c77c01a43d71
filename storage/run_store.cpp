#include <rrlab/storage/run_store.hpp>

#include <cmath>
#include <limits>

#include <rrlab/storage/database.hpp>
#include <rrlab/storage/disk_reserve.hpp>
#include <rrlab/storage/migrations.hpp>

namespace rrlab::storage {

namespace {

// The last column: a sweep run's identity, from sweep_runs (NULL for other runs).
constexpr const char* kRunColumns =
    "id, scenario_name, scenario, method, params, seed, mode, created, status, frames, summary, dof, "
    "diagnostic_names, source_run, compare_group, frame_bytes, "
    "(SELECT json_object('sweep', w.sweep, 'case', w.scenario_key, 'config', w.config_key, 'family', w.family, "
    "'success', json(CASE w.success WHEN 0 THEN 'false' ELSE 'true' END), 'failure_mode', w.failure_mode, "
    "'failure_t', w.failure_t) FROM sweep_runs w WHERE w.run_id = runs.id)";

RunRecord read_run(const Statement& s) {
  RunRecord r;
  r.id = s.column_int(0);
  r.scenario_name = s.column_text(1);
  r.scenario_json = s.column_text(2);
  r.method = s.column_text(3);
  r.params_json = s.column_text(4);
  r.seed = std::uint64_t(s.column_int(5));
  r.mode = s.column_text(6);
  r.created = s.column_text(7);
  r.status = s.column_text(8);
  r.frames = s.column_int(9);
  if (!s.is_null(10)) r.summary_json = s.column_text(10);
  r.dof = int(s.column_int(11));
  r.diagnostic_names_json = s.column_text(12);
  if (!s.is_null(13)) r.source_run = s.column_int(13);
  if (!s.is_null(14)) r.compare_group = s.column_int(14);
  r.frame_bytes = s.column_int(15);
  if (!s.is_null(16)) r.sweep_json = s.column_text(16);
  return r;
}

}  // namespace

RunStore::RunStore(const std::string& path, std::int64_t reserve_bytes)
    : reserve_(std::make_unique<DiskReserve>(path + "-reserve", reserve_bytes)), db_(std::make_unique<Database>(path)) {
  with_reserve([&] {  // opening on a full disk needs room for the journal too
    {
      // a new file gives deleted runs' pages back to the disk (set before any table exists)
      Statement pages = db_->prepare("PRAGMA page_count");
      if (pages.step() && pages.column_int(0) == 0) db_->exec("PRAGMA auto_vacuum=INCREMENTAL");
    }
    db_->exec("PRAGMA journal_mode=WAL");
    db_->exec("PRAGMA synchronous=NORMAL");
    db_->exec("PRAGMA foreign_keys=ON");
    Transaction tx(*db_);
    migrated_from_ = migrate_to_current(*db_);
    Statement mark = db_->prepare("UPDATE runs SET status = 'interrupted' WHERE status IN ('running', 'paused')");
    mark.step();
    interrupted_at_open_ = db_->changes();
    tx.commit();
  });
  finish_pending_deletes();
  {
    Statement total = db_->prepare("SELECT COALESCE(SUM(frame_bytes), 0) FROM runs");
    total.step();
    total_frame_bytes_ = total.column_int(0);
  }
  // a second connection for reads: in WAL mode readers never wait for the writer
  read_db_ = std::make_unique<Database>(path);
  read_db_->exec("PRAGMA query_only=ON");
}

RunStore::~RunStore() = default;

void RunStore::recording_faults(const std::function<void()>& write) {
  try {
    write();
  } catch (const StorageError& e) {
    if (e.write_fault()) {
      std::lock_guard lock(fault_mutex_);
      fault_ = WriteFault{e.fault(), e.what()};
    }
    throw;
  }
}

std::optional<WriteFault> RunStore::write_fault() {
  std::lock_guard lock(fault_mutex_);
  return fault_;
}

bool RunStore::probe_write() {
  if (!reserve_->take()) {  // no room for the reserve: still full for anything but deletes
    std::lock_guard lock(fault_mutex_);
    fault_ = WriteFault{StorageFault::full, "no room for the reserve kept for deletes"};
    return false;
  }
  try {
    recording_faults([&] {
      std::lock_guard lock(mutex_);
      {
        Transaction tx(*db_);
        // room for a batch of the frame writer: 1024 frames of a 64-joint arm (1.1 KB each)
        db_->exec("INSERT INTO storage_probe(bytes) VALUES (zeroblob(1048576))");
        tx.commit();
      }
      db_->exec("DELETE FROM storage_probe");
    });
  } catch (const StorageError& e) {
    if (e.write_fault()) return false;
    throw;
  }
  {
    std::lock_guard lock(fault_mutex_);
    fault_.reset();
  }
  finish_pending_deletes();  // deletes that met a full disk end now that there is room
  return true;
}

void RunStore::set_query_only() {
  std::lock_guard lock(mutex_);
  db_->exec("PRAGMA query_only=ON");
}

void RunStore::set_max_page_count(std::int64_t pages) {
  std::lock_guard lock(mutex_);
  db_->exec("PRAGMA max_page_count = " + std::to_string(pages));
}

std::int64_t RunStore::create_run(const NewRun& run) {
  std::int64_t id = 0;
  recording_faults([&] {
  std::lock_guard lock(mutex_);
  Statement s = db_->prepare(
      "INSERT INTO runs(scenario_name, scenario, method, params, seed, mode, created, status, dof, "
      "diagnostic_names, source_run, compare_group) VALUES (?,?,?,?,?,?,?,'running',?,?,?,?)");
  s.bind(1, run.scenario_name).bind(2, run.scenario_json).bind(3, run.method).bind(4, run.params_json);
  s.bind(5, std::int64_t(run.seed)).bind(6, run.mode).bind(7, utc_now()).bind(8, run.dof);
  s.bind(9, run.diagnostic_names_json);
  if (run.source_run) s.bind(10, *run.source_run); else s.bind_null(10);
  if (run.compare_group) s.bind(11, *run.compare_group); else s.bind_null(11);
  s.step();
  id = db_->last_insert_id();
  });
  return id;
}

void RunStore::set_status(std::int64_t id, std::string_view status) {
  recording_faults([&] {
    std::lock_guard lock(mutex_);
    db_->prepare("UPDATE runs SET status = ? WHERE id = ?").bind(1, status).bind(2, id).step();
  });
}

void RunStore::set_compare_group(std::int64_t id, std::int64_t group) {
  recording_faults([&] {
    std::lock_guard lock(mutex_);
    db_->prepare("UPDATE runs SET compare_group = ? WHERE id = ?").bind(1, group).bind(2, id).step();
  });
}

void RunStore::finish_run(std::int64_t id, std::string_view status, const std::string& summary_json) {
  recording_faults([&] {
    std::lock_guard lock(mutex_);
    db_->prepare("UPDATE runs SET status = ?, summary = ? WHERE id = ?")
        .bind(1, status)
        .bind(2, summary_json)
        .bind(3, id)
        .step();
  });
}

namespace {
constexpr const char* kInsertEvent = "INSERT INTO events(run_id, seq, step, kind, payload) VALUES (?,?,?,?,?)";

void bind_event(Statement& insert, std::int64_t run, const StoredEvent& e) {
  insert.bind(1, run).bind(2, e.seq).bind(3, e.step).bind(4, e.kind).bind(5, e.payload_json);
}
}  // namespace

void RunStore::add_event(std::int64_t run, const StoredEvent& e) {
  recording_faults([&] {
    std::lock_guard lock(mutex_);
    Statement insert = db_->prepare(kInsertEvent);
    bind_event(insert, run, e);
    insert.step();
  });
}

void RunStore::add_frames(const std::vector<std::pair<std::int64_t, StoredFrame>>& frames,
                          const std::vector<std::pair<std::int64_t, StoredEvent>>& events) {
  if (frames.empty() && events.empty()) return;
  recording_faults([&] {
  std::lock_guard lock(mutex_);
  Transaction tx(*db_);
  if (!events.empty()) {
    Statement insert = db_->prepare(kInsertEvent);
    for (const auto& [run_id, e] : events) {
      bind_event(insert, run_id, e);
      insert.step();
      insert.reset();
    }
  }
  if (frames.empty()) {
    tx.commit();
    return;
  }
  Statement insert = db_->prepare(
      "INSERT INTO frames(run_id, seq, step, t, task_error, min_distance, collided, data) "
      "VALUES (?,?,?,?,?,?,?,?)");
  Statement count = db_->prepare("UPDATE runs SET frames = frames + ?, frame_bytes = frame_bytes + ? WHERE id = ?");
  std::int64_t run = frames.front().first, in_run = 0, bytes = 0, all_bytes = 0;
  const auto flush_count = [&] {
    count.bind(1, in_run).bind(2, bytes).bind(3, run).step();
    count.reset();
  };
  for (const auto& [run_id, f] : frames) {
    if (run_id != run) {
      flush_count();
      run = run_id;
      in_run = 0;
      bytes = 0;
    }
    bytes += std::int64_t(f.data.size());
    all_bytes += std::int64_t(f.data.size());
    insert.bind(1, run_id).bind(2, f.seq).bind(3, f.step).bind(4, f.t).bind(5, f.task_error);
    if (std::isfinite(f.min_distance)) insert.bind(6, f.min_distance); else insert.bind_null(6);
    insert.bind(7, f.collided ? 1 : 0).bind_blob(8, f.data);
    insert.step();
    insert.reset();
    ++in_run;
  }
  flush_count();
  tx.commit();
  total_frame_bytes_ += all_bytes;
  });
}

// A write that meets a full disk gets the reserve back a step at a time
// until it fits (or none is left): a delete takes only the room it needs.
void RunStore::with_reserve(const std::function<void()>& write) {
  for (;;) {
    try {
      recording_faults(write);
      return;
    } catch (const StorageError& e) {
      if (e.fault() != StorageFault::full || !reserve_->release()) throw;
    }
  }
}

void RunStore::finish_pending_deletes() {
  std::vector<std::int64_t> pending;
  {
    std::lock_guard lock(mutex_);
    Statement deleting = db_->prepare("SELECT id FROM runs WHERE status = 'deleting'");
    while (deleting.step()) pending.push_back(deleting.column_int(0));
  }
  for (const std::int64_t id : pending) {
    try {
      finish_deleting(id);
    } catch (const StorageError& e) {
      if (!e.write_fault()) throw;  // a full or read-only file: finished later; the run stays hidden
    }
  }
}

bool RunStore::delete_run(std::int64_t id) {
  bool marked = false;
  with_reserve([&] {
    std::lock_guard lock(mutex_);
    db_->prepare("UPDATE runs SET status = 'deleting' WHERE id = ?").bind(1, id).step();
    marked = db_->changes() == 1;
  });
  if (!marked) return false;
  finish_deleting(id);
  return true;
}

void RunStore::finish_deleting(std::int64_t id) {
  constexpr int kFramesPerChunk = 512;  // about 0.6 MB of journal for a 64-joint arm's frames
  for (bool more = true; more;) {
    with_reserve([&] {
      std::lock_guard lock(mutex_);
      Transaction tx(*db_);
      Statement chunk = db_->prepare(
          "DELETE FROM frames WHERE run_id = ?1 AND seq IN (SELECT seq FROM frames WHERE run_id = ?1 ORDER BY seq LIMIT ?2)");
      chunk.bind(1, id).bind(2, kFramesPerChunk).step();
      more = db_->changes() == kFramesPerChunk;
      tx.commit();
    });
    if (more) {
      std::lock_guard lock(mutex_);
      try {
        db_->exec("PRAGMA wal_checkpoint(PASSIVE)");  // the journal's room is reused by the next chunk
      } catch (const StorageError&) {
      }
    }
  }
  with_reserve([&] {
    std::lock_guard lock(mutex_);
    Transaction tx(*db_);
    std::int64_t bytes = 0;
    {
      Statement read = db_->prepare("SELECT frame_bytes FROM runs WHERE id = ?");
      read.bind(1, id);
      if (read.step()) bytes = read.column_int(0);
    }
    db_->prepare("DELETE FROM events WHERE run_id = ?").bind(1, id).step();
    db_->prepare("DELETE FROM runs WHERE id = ?").bind(1, id).step();
    tx.commit();
    total_frame_bytes_ -= bytes;
  });
  give_back_space();
  reserve_->take();
}

void RunStore::give_back_space() {
  // the write lock one statement at a time: the frame writer goes on between them
  const auto locked = [&](const char* sql) {
    std::lock_guard lock(mutex_);
    db_->exec(sql);
  };
  try {
    bool incremental = false;
    {
      std::lock_guard lock(mutex_);
      Statement mode = db_->prepare("PRAGMA auto_vacuum");
      incremental = mode.step() && mode.column_int(0) == 2;  // files made before it: pages reused, not returned
    }
    for (bool free_pages = incremental; free_pages;) {
      locked("PRAGMA incremental_vacuum(256)");  // 1 MiB of pages at a time
      locked("PRAGMA wal_checkpoint(PASSIVE)");
      std::lock_guard lock(mutex_);
      Statement count = db_->prepare("PRAGMA freelist_count");
      free_pages = count.step() && count.column_int(0) > 0;
    }
    locked("PRAGMA wal_checkpoint(TRUNCATE)");  // the journal's own room back to the disk
  } catch (const StorageError&) {
    // a full disk or a reader holding the journal: the pages stay free in the file and are reused
  }
}

std::optional<RunRecord> RunStore::run(std::int64_t id) {
  std::lock_guard lock(read_mutex_);
  Statement s = read_db_->prepare(std::string("SELECT ") + kRunColumns + " FROM runs WHERE id = ? AND status != 'deleting'");
  s.bind(1, id);
  if (!s.step()) return std::nullopt;
  return read_run(s);
}

std::vector<RunRecord> RunStore::runs(const RunFilter& filter) {
  std::lock_guard lock(read_mutex_);
  Statement s = read_db_->prepare(std::string("SELECT ") + kRunColumns +
                             " FROM runs WHERE (?1 IS NULL OR scenario_name = ?1) AND (?2 IS NULL OR method = ?2)"
                             " AND (?3 IS NULL OR status = ?3) AND status != 'deleting'"
                             " AND (?6 IS NULL OR (?6 = '') = NOT EXISTS (SELECT 1 FROM sweep_runs w WHERE w.run_id = runs.id"
                             " AND (?6 = '' OR w.sweep = ?6)))"
                             " AND (?7 IS NULL OR compare_group = ?7)"
                             " ORDER BY id DESC LIMIT ?4 OFFSET ?5");
  if (filter.scenario) s.bind(1, *filter.scenario); else s.bind_null(1);
  if (filter.method) s.bind(2, *filter.method); else s.bind_null(2);
  if (filter.status) s.bind(3, *filter.status); else s.bind_null(3);
  s.bind(4, filter.limit).bind(5, filter.offset);
  if (filter.sweep) s.bind(6, *filter.sweep); else s.bind_null(6);
  if (filter.compare_group) s.bind(7, *filter.compare_group); else s.bind_null(7);
  std::vector<RunRecord> out;
  while (s.step()) out.push_back(read_run(s));
  return out;
}

std::vector<StoredEvent> RunStore::events(std::int64_t run) {
  std::lock_guard lock(read_mutex_);
  Statement s = read_db_->prepare("SELECT seq, step, kind, payload FROM events WHERE run_id = ? ORDER BY id");
  s.bind(1, run);
  std::vector<StoredEvent> out;
  while (s.step()) out.push_back({s.column_int(0), s.column_int(1), s.column_text(2), s.column_text(3)});
  return out;
}

void RunStore::frames(std::int64_t run, std::int64_t from, std::int64_t to, std::int64_t stride,
                      const std::function<bool(const StoredFrame&)>& visit) {
  std::lock_guard lock(read_mutex_);
  Statement s = read_db_->prepare(
      "SELECT seq, step, t, task_error, min_distance, collided, data FROM frames WHERE run_id = ?1 "
      "AND seq BETWEEN ?2 AND ?3 AND (seq - ?2) % ?4 = 0 ORDER BY seq");
  s.bind(1, run).bind(2, from).bind(3, to).bind(4, stride < 1 ? 1 : stride);
  StoredFrame f;
  while (s.step()) {
    f.seq = s.column_int(0);
    f.step = s.column_int(1);
    f.t = s.column_double(2);
    f.task_error = s.column_double(3);
    f.min_distance = s.is_null(4) ? std::numeric_limits<double>::infinity() : s.column_double(4);
    f.collided = s.column_int(5) != 0;
    f.data.assign(s.column_blob(6));
    if (!visit(f)) break;
  }
}

bool RunStore::put_scenario(const std::string& name, const std::string& json) {
  return put_scenario(name, json, std::numeric_limits<std::int64_t>::max()) == PutScenario::added;
}

PutScenario RunStore::put_scenario(const std::string& name, const std::string& json, std::int64_t max_count) {
  PutScenario result = PutScenario::exists;
  recording_faults([&] {
    std::lock_guard lock(mutex_);
    {
      Statement exists = db_->prepare("SELECT 1 FROM scenarios WHERE name = ?");
      exists.bind(1, name);
      if (exists.step()) return;
    }
    Statement count = db_->prepare("SELECT COUNT(*) FROM scenarios");
    count.step();
    if (count.column_int(0) >= max_count) {
      result = PutScenario::full;
      return;
    }
    Statement s = db_->prepare("INSERT OR IGNORE INTO scenarios(name, json, created) VALUES (?,?,?)");
    s.bind(1, name).bind(2, json).bind(3, utc_now()).step();
    if (db_->changes() == 1) result = PutScenario::added;
  });
  return result;
}

std::int64_t RunStore::scenario_count() {
  std::lock_guard lock(read_mutex_);
  Statement s = read_db_->prepare("SELECT COUNT(*) FROM scenarios");
  s.step();
  return s.column_int(0);
}

std::optional<std::string> RunStore::scenario(const std::string& name) {
  std::lock_guard lock(read_mutex_);
  Statement s = read_db_->prepare("SELECT json FROM scenarios WHERE name = ?");
  s.bind(1, name);
  if (!s.step()) return std::nullopt;
  return s.column_text(0);
}

std::vector<std::string> RunStore::scenario_names() {
  std::lock_guard lock(read_mutex_);
  Statement s = read_db_->prepare("SELECT name FROM scenarios ORDER BY name");
  std::vector<std::string> out;
  while (s.step()) out.push_back(s.column_text(0));
  return out;
}

std::string RunStore::integrity_check() {
  std::lock_guard lock(mutex_);
  Statement s = db_->prepare("PRAGMA integrity_check");
  std::string out;
  while (s.step()) out += (out.empty() ? "" : "; ") + s.column_text(0);
  return out;
}

}  // namespace rrlab::storage
