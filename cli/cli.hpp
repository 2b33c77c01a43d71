// Subcommands of the rrlab executable.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <rrlab/storage/quotas.hpp>

namespace rrlab::cli {

struct RunOptions {
  std::string scenario_file;  // a scenario, or a run record (GET /api/runs/{id}/record)
  std::optional<std::string> method;
  std::vector<std::string> params;  // NAME=VALUE
  std::optional<long> steps;
  std::optional<std::string> out_csv;
  std::optional<std::string> db;  // store the run (mode "batch") in this database
};

struct ServeOptions {
  std::string host = "127.0.0.1";
  unsigned short port = 8080;
  std::string db = "data/rrlab.db";
  std::optional<std::string> web_dir, scenarios_dir;
  int threads = 2;
  double display_hz = 60;
  std::size_t body_limit = 1 << 20;
  int ws_stall_ms = 5000;  // a WebSocket write pending this long drops the client
  std::size_t export_memory = 64 << 20;  // bytes all streamed exports may hold at once (128 KiB each)
  int connections_per_address = 256, max_websockets = 1024, websockets_per_address = 128, websockets_per_client = 32;
  int websocket_fair_share = 8;                   // an address holding fewer may take the newcomer reserve
  std::optional<int> websocket_newcomer_reserve;  // unset: an eighth of max_websockets
  // quotas (server/app/run_manager.hpp ServerLimits has the defaults' reasons)
  Quotas quotas;  // --max-run-frames, --max-run-bytes, --max-total-bytes, --max-run-cost, --max-scenarios
  std::int64_t test_db_max_pages = 0;  // tests only: PRAGMA max_page_count on the write connection (0: none)
  bool test_db_read_only = false;       // tests only: PRAGMA query_only on the write connection
  int test_build_delay_ms = 0;          // tests only: each scenario build waits this long first
  std::vector<std::string> allow_hosts, allow_origins;  // beyond this server's own (net/request_guard.hpp)
  std::string token;             // --token or RRLAB_TOKEN: required for changes, WebSocket inputs and reads
  bool public_read = false;      // reads need no token
  bool allow_anonymous = false;  // serve a non-loopback address without a token
};

struct ReplayOptions {
  std::int64_t run_id = 0;
  std::string db;
  bool verify = false;
};

struct SweepOptions {
  std::string spec_file;
  std::string db;
  int jobs = 0;  // 0: one per hardware thread
  std::optional<std::string> shard;  // I/N
  std::optional<int> shards;         // N, the index from the array job's environment
  std::optional<std::string> out_csv;
  bool frames = false;
  std::optional<std::string> scenarios_dir;  // catalogue names
};

struct GenerateOptions {
  std::string family;                         // or, with `perturb`, empty
  std::string perturb;                        // a scenario file or catalogue name: its perturbation family
  std::optional<std::string> scenarios_dir;   // the catalogue (perturb)
  std::uint64_t seed = 1;
  int count = 1, first = 0;
  std::vector<int> cases;            // exactly these indices (a report's unsolved cases), instead of count/first
  std::vector<std::string> options;  // KEY=VALUE, VALUE as JSON where it parses
  std::string out_dir;
  bool list = false;  // print the families (name, tab, summary) instead
};

struct MergeOptions {
  std::string out_db;
  std::vector<std::string> in_dbs;
};

struct ReportOptions {
  std::string db;
  std::optional<std::string> sweep;
  std::string format = "md";
  std::optional<std::string> out;
};

// Exit codes: 0 success, 1 verification failed (replay), 2 bad input (message on stderr),
// 3 nothing to verify (replay --verify of a run that stored no frames).
int run(const RunOptions& options);
int methods();
int collisions(const std::string& scenario_file);
// generate: 0 every case written, 2 bad input (an option, an unknown family, an unwritable --out).
int generate(const GenerateOptions& options);
int serve(const ServeOptions& options);
int replay(const ReplayOptions& options);
// sweep: 0 every run stored, 1 some runs failed (named on stderr), 2 bad input,
// 130 interrupted (SIGINT/SIGTERM: the runs under way were finished and stored).
int sweep(const SweepOptions& options);
int merge(const MergeOptions& options);
int report(const ReportOptions& options);
// A directory given on the command line, else ./NAME, else the source tree's.
std::string find_dir(const std::optional<std::string>& given, const char* name);
// A database the command reads must exist (it never creates one): false, with
// the error on stderr, when `db` is not a file.
bool database_exists(const std::string& db);

}  // namespace rrlab::cli
