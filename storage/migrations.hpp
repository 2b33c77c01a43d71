// Schema migrations by schema_version: a database written by an older rrlab
// is brought to the current schema when it is opened, in one transaction (a
// migration that fails leaves the file as it was). A database written by a
// newer rrlab is refused rather than guessed at.
#pragma once

namespace rrlab::storage {

class Database;

struct Migration {
  int to_version;           // applied to a database at to_version - 1
  const char* description;  // for the log and errors
  const char* sql;
};

// The version this rrlab writes (schema.sql's "Version N").
int current_schema_version();

// Every migration, oldest first; the last one's to_version is kSchemaVersion.
const Migration* migrations_begin();
const Migration* migrations_end();

// Brings `db` to kSchemaVersion (creating the schema in an empty file).
// Returns the version the file had (0: new). Throws StorageError. Must run
// inside a transaction.
int migrate_to_current(Database& db);

}  // namespace rrlab::storage
