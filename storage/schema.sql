-- rrlab storage schema. Version 3. A new file gets this whole schema; an older
-- one is migrated step by step (storage/migrations.cpp), then this is applied
-- again, which only adds what is missing (every statement is IF NOT EXISTS).
-- A run's frames are numbered by seq, the count of steps taken in the run
-- (a reset starts the simulation's step count over, seq goes on). An event
-- took effect before the frame with the same seq.
CREATE TABLE IF NOT EXISTS schema_version (version INTEGER NOT NULL);

CREATE TABLE IF NOT EXISTS runs (
  id               INTEGER PRIMARY KEY AUTOINCREMENT,
  scenario_name    TEXT NOT NULL,
  scenario         TEXT NOT NULL,              -- scenario JSON as given
  method           TEXT NOT NULL,              -- at the start
  params           TEXT NOT NULL,              -- JSON {name: value} at the start
  seed             INTEGER NOT NULL,
  mode             TEXT NOT NULL,              -- live | batch | resimulation
  created          TEXT NOT NULL,              -- UTC, ISO 8601
  status           TEXT NOT NULL,              -- running | paused | completed | stopped | interrupted | failed | deleting (hidden)
  frames           INTEGER NOT NULL DEFAULT 0, -- stored frames
  summary          TEXT,                       -- JSON, when ended
  dof              INTEGER NOT NULL,
  diagnostic_names TEXT NOT NULL,              -- JSON array, of the starting method
  source_run       INTEGER,                    -- a re-simulation: the run it re-simulates
  compare_group    INTEGER,                    -- runs started together by /api/compare
  frame_bytes      INTEGER NOT NULL DEFAULT 0  -- bytes of stored frame data (version 2)
);
CREATE INDEX IF NOT EXISTS runs_scenario ON runs(scenario_name);
CREATE INDEX IF NOT EXISTS runs_method ON runs(method);

CREATE TABLE IF NOT EXISTS frames (
  run_id       INTEGER NOT NULL REFERENCES runs(id) ON DELETE CASCADE,
  seq          INTEGER NOT NULL,
  step         INTEGER NOT NULL,
  t            REAL NOT NULL,
  task_error   REAL,
  min_distance REAL,                           -- NULL: no obstacles (+inf)
  collided     INTEGER NOT NULL,
  data         BLOB NOT NULL,                  -- every deterministic field, packed (frame_codec.hpp)
  PRIMARY KEY (run_id, seq)
) WITHOUT ROWID;

CREATE TABLE IF NOT EXISTS events (
  id       INTEGER PRIMARY KEY AUTOINCREMENT,
  run_id   INTEGER NOT NULL REFERENCES runs(id) ON DELETE CASCADE,
  seq      INTEGER NOT NULL,
  step     INTEGER NOT NULL,
  kind     TEXT NOT NULL,
  payload  TEXT NOT NULL                       -- JSON
);
CREATE INDEX IF NOT EXISTS events_run ON events(run_id, id);

CREATE TABLE IF NOT EXISTS scenarios (
  name     TEXT PRIMARY KEY,
  json     TEXT NOT NULL,
  created  TEXT NOT NULL
);

-- Sweeps (rrlab sweep): one row per stored sweep run. (sweep, key) is the
-- run's identity across invocations, shards and merges; success is judged by
-- the sweep spec's criteria when the run is stored, so reports need no spec.
-- Added after version 1 shipped: CREATE ... IF NOT EXISTS adds it to existing
-- databases at open.
CREATE TABLE IF NOT EXISTS sweep_runs (
  sweep        TEXT NOT NULL,
  key          TEXT NOT NULL,                  -- sweep/scenario_key/config_key/seed
  run_id       INTEGER NOT NULL REFERENCES runs(id) ON DELETE CASCADE,
  scenario_key TEXT NOT NULL,                  -- file:NAME | gen:FAMILY:SEED:INDEX
  config_key   TEXT NOT NULL,                  -- method{param=value,...}
  family       TEXT NOT NULL,                  -- generator family, or "file"
  success      INTEGER NOT NULL,
  failure_mode TEXT,                           -- a failed run's first failure (version 3; NULL: passed, or stored before)
  failure_t    REAL,                           -- s, when it began
  PRIMARY KEY (sweep, key)
) WITHOUT ROWID;
CREATE INDEX IF NOT EXISTS sweep_runs_run ON sweep_runs(run_id);

-- RunStore::probe_write commits 1 MiB here and deletes it again: whether a
-- full disk or a read-only file can be written again. Always empty. Added
-- without a version change (IF NOT EXISTS adds it at open).
CREATE TABLE IF NOT EXISTS storage_probe (bytes BLOB);
