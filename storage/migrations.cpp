#include <rrlab/storage/migrations.hpp>

#include <iterator>
#include <string>

#include <rrlab/storage/database.hpp>

#include "storage/schema_sql.hpp"

namespace rrlab::storage {

namespace {

// To add a migration: bump "Version N" in schema.sql (the full schema a new
// file gets), change the tables there, and append the step from N-1 here. The
// test opens a committed database of every older version.
constexpr Migration kMigrations[] = {
    {2, "runs.frame_bytes: bytes of stored frame data per run, counted for existing runs",
     "ALTER TABLE runs ADD COLUMN frame_bytes INTEGER NOT NULL DEFAULT 0;"
     "UPDATE runs SET frame_bytes = (SELECT COALESCE(SUM(length(data)), 0) FROM frames "
     "WHERE frames.run_id = runs.id);"},
    // sweep_runs may be missing in a version-1 file (it was added without a
    // version change): made in its version-2 shape first, then widened
    {3, "sweep_runs.failure_mode and failure_t: a failed sweep run's first failure and when it began",
     "CREATE TABLE IF NOT EXISTS sweep_runs (sweep TEXT NOT NULL, key TEXT NOT NULL, "
     "run_id INTEGER NOT NULL REFERENCES runs(id) ON DELETE CASCADE, scenario_key TEXT NOT NULL, "
     "config_key TEXT NOT NULL, family TEXT NOT NULL, success INTEGER NOT NULL, PRIMARY KEY (sweep, key)) "
     "WITHOUT ROWID;"
     "ALTER TABLE sweep_runs ADD COLUMN failure_mode TEXT;"
     "ALTER TABLE sweep_runs ADD COLUMN failure_t REAL;"},
};
static_assert(std::size(kMigrations) > 0 && kMigrations[std::size(kMigrations) - 1].to_version == kSchemaVersion,
              "schema.sql's version must be the last migration's");

bool has_table(Database& db, const char* name) {
  Statement s = db.prepare("SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = ?");
  s.bind(1, std::string_view(name));
  return s.step();
}

}  // namespace

int current_schema_version() { return kSchemaVersion; }

const Migration* migrations_begin() { return std::begin(kMigrations); }
const Migration* migrations_end() { return std::end(kMigrations); }

int migrate_to_current(Database& db) {
  if (!has_table(db, "schema_version")) {
    db.exec(kSchemaSql);
    db.prepare("INSERT INTO schema_version(version) VALUES (?)").bind(1, kSchemaVersion).step();
    return 0;
  }
  Statement read = db.prepare("SELECT version FROM schema_version");
  if (!read.step()) throw StorageError("the database has a schema_version table without a version");
  const int version = int(read.column_int(0));
  if (version > kSchemaVersion)
    throw StorageError("the database was written by a newer rrlab (schema version " + std::to_string(version) +
                       "; this rrlab reads versions up to " + std::to_string(kSchemaVersion) +
                       "): open it with that rrlab or a newer one");
  if (version < 1) throw StorageError("the database has an invalid schema version " + std::to_string(version));
  if (version == kSchemaVersion) return version;  // nothing to write: a read-only file opens too
  for (const Migration* m = migrations_begin(); m != migrations_end(); ++m) {
    if (m->to_version <= version) continue;
    try {
      db.exec(m->sql);
    } catch (const StorageError& e) {
      throw StorageError("migrating the database to schema version " + std::to_string(m->to_version) + " (" +
                         m->description + ") failed: " + e.what());
    }
  }
  // Tables and indexes a version added without changing older ones.
  db.exec(kSchemaSql);
  db.prepare("UPDATE schema_version SET version = ?").bind(1, kSchemaVersion).step();
  return version;
}

}  // namespace rrlab::storage
