// Runs, frames, events and user scenarios in one SQLite file (schema.sql).
// Thread-safe: a write connection and a read connection, each behind its own
// mutex (SQLite in WAL mode with synchronous=NORMAL: a crash loses at most the
// last uncommitted batch, and readers never block the writer).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace rrlab::storage {

class Database;
class DiskReserve;
enum class StorageFault;

// A write that failed because the disk is full or the file read-only (the
// condition a new run must wait out): its kind and SQLite's message.
struct WriteFault {
  StorageFault fault;
  std::string message;
};

enum class PutScenario { added, exists, full };

struct NewRun {
  std::string scenario_name, scenario_json, method, params_json, mode;
  std::uint64_t seed = 1;
  int dof = 0;
  std::string diagnostic_names_json = "[]";
  std::optional<std::int64_t> source_run, compare_group;
};

struct RunRecord {
  std::int64_t id = 0;
  std::string scenario_name, scenario_json, method, params_json, mode, created, status;
  std::uint64_t seed = 1;
  std::int64_t frames = 0;
  std::int64_t frame_bytes = 0;  // stored frame data
  std::optional<std::string> summary_json;
  int dof = 0;
  std::string diagnostic_names_json;
  std::optional<std::int64_t> source_run, compare_group;
  // a sweep run's {sweep, case, config, family, success, failure_mode, failure_t}
  std::optional<std::string> sweep_json;
};

struct StoredEvent {
  std::int64_t seq = 0, step = 0;
  std::string kind, payload_json;
};

struct StoredFrame {
  std::int64_t seq = 0, step = 0;
  double t = 0, task_error = 0, min_distance = 0;
  bool collided = false;
  std::string data;  // frame_codec.hpp
};

// A sweep run's identity and verdict (table sweep_runs).
struct SweepRunRow {
  std::string sweep, key, scenario_key, config_key, family;
  bool success = false;
  // a failed run's first failure (sweep/failure_watch.hpp) and when it began;
  // none for a run that passed or one stored before rrlab recorded them
  std::optional<std::string> failure_mode = std::nullopt;
  std::optional<double> failure_t = std::nullopt;
};

// A run stored whole, once it has ended: status "completed".
struct FinishedRun {
  NewRun run;
  std::string summary_json;
  std::optional<std::string> created;  // kept when copying a stored run; now otherwise
  std::vector<StoredFrame> frames;     // may be empty
  std::vector<StoredEvent> events;
};

// A stored sweep run with what reports and merges read of its run.
struct SweepRunEntry {
  SweepRunRow row;
  std::int64_t run_id = 0;
  std::uint64_t seed = 0;
  std::optional<std::string> summary_json;
  std::optional<std::string> difficulty_json = std::nullopt;  // the scenario's witness.difficulty (generated cases)
  std::int64_t frames = 0;                                    // stored frames (a sweep stores none unless asked)
};

struct RunFilter {
  std::optional<std::string> scenario, method, status;
  std::optional<std::string> sweep;  // a sweep's name: its runs; "" : runs of no sweep
  std::optional<std::int64_t> compare_group;  // the runs /api/compare started together (the first lane's id)
  int limit = 100, offset = 0;
};

class RunStore {
 public:
  // Opens (creating if missing) and migrates; runs left "running" or "paused"
  // by a previous process are marked "interrupted", and deletions a previous
  // process left unfinished are finished. `reserve_bytes`: the room kept
  // beside the file (PATH-reserve) for deletes on a full disk (disk_reserve.hpp;
  // the server keeps 8 MiB, the command line none).
  explicit RunStore(const std::string& path, std::int64_t reserve_bytes = 0);
  ~RunStore();

  int interrupted_at_open() const { return interrupted_at_open_; }
  // The schema version the file had when opened (0: created now); below
  // kSchemaVersion when it was migrated.
  int migrated_from() const { return migrated_from_; }

  std::int64_t create_run(const NewRun& run);
  void set_status(std::int64_t id, std::string_view status);
  void set_compare_group(std::int64_t id, std::int64_t group);
  void finish_run(std::int64_t id, std::string_view status, const std::string& summary_json);
  void add_event(std::int64_t run, const StoredEvent& event);
  // Frames of one or more runs in one transaction, with input events of
  // those or other runs (the frame writer's batch); updates the runs' frame counts.
  void add_frames(const std::vector<std::pair<std::int64_t, StoredFrame>>& frames,
                  const std::vector<std::pair<std::int64_t, StoredEvent>>& events = {});

  // Deletes a run with its frames and events in one transaction; false when
  // there is no such run. Whether it may be deleted (not live) is the caller's
  // business. Runs that name it (source_run, compare_group) keep the number.
  bool delete_run(std::int64_t id);  // also finishes a deletion of `id` that a full disk interrupted

  std::optional<RunRecord> run(std::int64_t id);
  std::vector<RunRecord> runs(const RunFilter& filter);
  std::vector<StoredEvent> events(std::int64_t run);
  // Frames with from <= seq <= to, every stride-th; visit returns false to stop.
  void frames(std::int64_t run, std::int64_t from, std::int64_t to, std::int64_t stride,
              const std::function<bool(const StoredFrame&)>& visit);

  // User scenarios (validated by the caller).
  bool put_scenario(const std::string& name, const std::string& json);  // false: exists
  // Adds unless the name exists or `max_count` scenarios are stored (checked
  // and inserted under the write lock: concurrent adds cannot pass the cap).
  PutScenario put_scenario(const std::string& name, const std::string& json, std::int64_t max_count);
  std::int64_t scenario_count();
  std::optional<std::string> scenario(const std::string& name);
  std::vector<std::string> scenario_names();

  // Sweeps (run_store_sweeps.cpp). Stores the run, its frames and events and
  // its sweep_runs row in one transaction; nullopt, storing nothing, when
  // (row.sweep, row.key) is stored already.
  std::optional<std::int64_t> add_sweep_run(const FinishedRun& run, const SweepRunRow& row);
  std::vector<std::string> sweep_keys(const std::string& sweep);
  // Every sweep's runs, or one sweep's, ordered by sweep then key. `cancel`
  // set while reading (a server shutting down): returns what it has read.
  std::vector<SweepRunEntry> sweep_runs(const std::optional<std::string>& sweep,
                                        const std::atomic<bool>* cancel = nullptr);

  // One page of a sweep's runs (ordered by key) matching the filter, and how
  // many match: read in SQL, so a page costs its own rows only.
  struct SweepRunFilter {
    std::optional<std::string> family;  // the report's family: a generator family, or a file's scenario key
    std::optional<std::string> config, failure_mode;
    std::optional<bool> success;
  };
  std::vector<SweepRunEntry> sweep_runs_page(const std::string& sweep, const SweepRunFilter& filter,
                                             std::int64_t limit, std::int64_t offset, std::int64_t& total);
  // The next `limit` matching runs whose keys follow `after_key` (keyset
  // paging: a stream of every run reads each row once, whatever is stored
  // or deleted meanwhile).
  std::vector<SweepRunEntry> sweep_runs_after(const std::string& sweep, const SweepRunFilter& filter,
                                              const std::string& after_key, std::int64_t limit);

  std::string integrity_check();  // "ok" when sound

  // Bytes of frame data stored in the file: SUM(runs.frame_bytes) at open,
  // kept current by every write and delete of this store.
  std::int64_t total_frame_bytes() const { return total_frame_bytes_; }

  // The last write that failed with a full disk or a read-only file, until a
  // probe_write() succeeds. Every write method records such a failure (and
  // rethrows it as a StorageError whose fault() says which).
  std::optional<WriteFault> write_fault();
  // Tries a real write (1 MiB, a frame batch, committed to table
  // storage_probe, then deleted: a file with less room stays "full").
  // Success clears the recorded fault; failure records it. True when writable.
  bool probe_write();

  // Tests only: caps the file at `pages` pages on the write connection
  // (PRAGMA max_page_count), so that tests can fill the "disk".
  void set_max_page_count(std::int64_t pages);
  // Tests only: every later write on the write connection fails with
  // SQLITE_READONLY (PRAGMA query_only), as with a file opened read-only.
  void set_query_only();

 private:
  // Runs a write; a StorageError with a write fault is recorded, then rethrown.
  void recording_faults(const std::function<void()>& write);
  // Runs a write that makes room (a delete); on a full disk it gives back the
  // reserve and tries once more.
  void with_reserve(const std::function<void()>& write);
  // The deletion of a run marked "deleting": its frames a chunk at a time (the
  // journal stays small: a full disk needs little room), then its row.
  void finish_deleting(std::int64_t id);
  // Finishes the deletions a full disk (or an earlier process) left: their runs stay hidden meanwhile.
  void finish_pending_deletes();
  // Empties the journal and, in a file with incremental auto-vacuum, gives
  // free pages back to the disk (stops quietly on a full disk).
  void give_back_space();

  std::mutex mutex_, read_mutex_, fault_mutex_;
  std::atomic<std::int64_t> total_frame_bytes_{0};
  std::optional<WriteFault> fault_;  // guarded by fault_mutex_
  std::unique_ptr<DiskReserve> reserve_;
  std::unique_ptr<Database> db_;       // writes (and integrity checks)
  std::unique_ptr<Database> read_db_;  // reads: exports never hold up the frame writer
  int interrupted_at_open_ = 0;
  int migrated_from_ = 0;
};

}  // namespace rrlab::storage
