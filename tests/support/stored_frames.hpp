// Test-only writes to a run database, with the tests' own SQL on the file
// (the sqlite3 C API): what no production code may do, so RunStore does not
// offer it. Link SQLite::SQLite3.
#pragma once

#include <sqlite3.h>

#include <cstdint>
#include <stdexcept>
#include <string>

namespace rrlab::test {

// Overwrites the blob of frame `seq` of run `run` in the database file `db`
// (a tampered frame for tests of verification); throws unless exactly one
// frame changed. Safe while a server has the file open (WAL; waits for its lock).
inline void overwrite_frame_data(const std::string& db, std::int64_t run, std::int64_t seq, const std::string& data) {
  sqlite3* handle = nullptr;
  const auto fail = [&](const std::string& what) {
    const std::string message = what + ": " + (handle ? sqlite3_errmsg(handle) : "out of memory");
    sqlite3_close(handle);
    throw std::runtime_error("overwrite_frame_data(" + db + "): " + message);
  };
  if (sqlite3_open_v2(db.c_str(), &handle, SQLITE_OPEN_READWRITE, nullptr) != SQLITE_OK) fail("open");
  sqlite3_busy_timeout(handle, 30000);
  sqlite3_stmt* update = nullptr;
  if (sqlite3_prepare_v2(handle, "UPDATE frames SET data = ?1 WHERE run_id = ?2 AND seq = ?3", -1, &update, nullptr) !=
      SQLITE_OK)
    fail("prepare");
  sqlite3_bind_blob(update, 1, data.data(), int(data.size()), SQLITE_TRANSIENT);
  sqlite3_bind_int64(update, 2, run);
  sqlite3_bind_int64(update, 3, seq);
  const int stepped = sqlite3_step(update);
  sqlite3_finalize(update);
  if (stepped != SQLITE_DONE) fail("update");
  if (sqlite3_changes(handle) != 1)
    fail("no frame " + std::to_string(seq) + " of run " + std::to_string(run));
  sqlite3_close(handle);
}

}  // namespace rrlab::test
