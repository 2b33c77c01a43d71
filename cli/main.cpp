// rrlab: command line front end (serve, run, replay, methods, generate, sweep, merge, report).
#include <CLI/CLI.hpp>
#include <cstdint>
#include <limits>

#include <rrlab/generators/generators.hpp>
#include <rrlab/scenario/scenario.hpp>

#include "cli.hpp"
#include "whole_number.hpp"

// Stays whole (over 100 lines): it is the command line's option table, one
// subcommand after the other, so that this file and `rrlab --help` read alike.
int main(int argc, char** argv) {
  using rrlab::cli::whole_number_in;  // every integer option's check: its range, in decimal
  constexpr std::int64_t kInt64Max = std::numeric_limits<std::int64_t>::max();
  CLI::App app{"rrlab: redundancy-resolution lab"};
  app.require_subcommand(1);
  // the project(VERSION) of CMakeLists.txt, and the git commit when cmake last ran (if it was a git checkout)
  app.set_version_flag("--version", std::string("rrlab ") + RRLAB_VERSION +
                                        (std::string(RRLAB_GIT_COMMIT).empty() ? "" : " (git " RRLAB_GIT_COMMIT ")"));

  rrlab::cli::ServeOptions serve;
  CLI::App* serve_cmd = app.add_subcommand("serve", "serve the dashboard, REST and WebSocket API");
  serve_cmd->add_option("--host", serve.host, "address to bind (default 127.0.0.1: this machine only)");
  whole_number_in(serve_cmd->add_option("--port", serve.port, "port (0: any free port, printed at start)"), 0, 65535);
  serve_cmd->add_option("--db", serve.db, "SQLite database file (created if missing)");
  serve_cmd->add_option("--web", serve.web_dir, "directory of the dashboard's static files");
  serve_cmd->add_option("--scenarios", serve.scenarios_dir, "directory of scenario files");
  whole_number_in(serve_cmd->add_option("--threads", serve.threads, "I/O threads"), 1, 64);
  serve_cmd->add_option("--display-hz", serve.display_hz, "WebSocket frame rate")->check(CLI::Range(1.0, 240.0));
  whole_number_in(serve_cmd->add_option("--body-limit", serve.body_limit, "largest request body in bytes"), 1024,
                  std::int64_t(64) << 20);
  whole_number_in(serve_cmd->add_option("--ws-stall-ms", serve.ws_stall_ms,
                                        "drop a WebSocket client whose write is stuck this long"),
                  100, 600000);
  whole_number_in(serve_cmd->add_option("--export-memory", serve.export_memory,
                                        "bytes all streamed frame exports may hold at once, 128 KiB each (default "
                                        "67108864 = 64 MiB, 512 exports; beyond: 503 busy)"),
                  std::int64_t(128) << 10, std::int64_t(1) << 40);
  whole_number_in(serve_cmd->add_option("--connections-per-address", serve.connections_per_address,
                                        "TCP connections one address may hold (default 256; at the cap its oldest "
                                        "connection that waits for a request is closed for a new one)"),
                  4, 65536);
  whole_number_in(serve_cmd->add_option("--max-websockets", serve.max_websockets,
                                        "WebSocket clients in all (default 1024; a sixteenth kept for token holders, "
                                        "an eighth for new clients)"),
                  16, 65536);
  whole_number_in(serve_cmd->add_option("--websocket-newcomer-reserve", serve.websocket_newcomer_reserve,
                                        "WebSockets that clients without a token take only while their address holds "
                                        "fewer than --websocket-fair-share (default: an eighth of --max-websockets, "
                                        "128)"),
                  0, 65536);
  whole_number_in(serve_cmd->add_option("--websocket-fair-share", serve.websocket_fair_share,
                                        "an address without a token holding fewer WebSockets than this may take the "
                                        "newcomer reserve (default 8)"),
                  1, 65536);
  whole_number_in(serve_cmd->add_option("--websockets-per-address", serve.websockets_per_address,
                                        "WebSocket clients one address may hold (default 128)"),
                  1, 65536);
  whole_number_in(serve_cmd->add_option("--websockets-per-client", serve.websockets_per_client,
                                        "WebSocket clients of one client name (default 32)"),
                  1, 65536);
  whole_number_in(serve_cmd->add_option("--max-run-frames", serve.quotas.max_run_frames,
                                        "frames one run may store (default 1000000; a request for more steps is 413)"),
                  1, 100'000'000);
  whole_number_in(serve_cmd->add_option("--max-run-bytes", serve.quotas.max_run_bytes,
                                        "bytes of frames one run may store (default 268435456 = 256 MiB; beyond: 413)"),
                  1, std::int64_t(1) << 50);
  whole_number_in(serve_cmd->add_option("--max-total-bytes", serve.quotas.max_total_bytes,
                                        "bytes of frames all runs in the database may hold (default 8589934592 = 8 "
                                        "GiB; beyond: 507)"),
                  1, std::int64_t(1) << 60);
  serve_cmd->add_option("--max-run-cost", serve.quotas.max_run_cost,
                        "a request's cost estimate, DOF x (obstacles + 1) x steps summed over its runs (default 2e10, "
                        "about ten minutes of a core; beyond: 413)")
      ->check(CLI::Range(1.0, 1e18));
  whole_number_in(serve_cmd->add_option("--max-scenarios", serve.quotas.max_scenarios,
                                        "scenarios stored over REST (default 1000; beyond: 507)"),
                  0, 1'000'000);
  whole_number_in(serve_cmd->add_option("--max-live-per-address", serve.quotas.max_live_per_address,
                                        "live runs or compare groups one address may hold (default 16; a new one ends "
                                        "the address's oldest unwatched one, or is refused with 429 when every one is "
                                        "watched)"),
                  1, 65536);
  whole_number_in(serve_cmd->add_option("--live-reserve-bytes", serve.quotas.live_reserve_bytes,
                                        "bytes of --max-total-bytes a live run reserves at its start, at most (default "
                                        "16777216 = 16 MiB; later frames are stored while the total fits)"),
                  1, std::int64_t(1) << 50);
  whole_number_in(serve_cmd->add_option("--abandon-unwatched-s", serve.quotas.abandon_unwatched_s,
                                        "a live run with no WebSocket client and no REST call for it this long after "
                                        "its start ends as abandoned (default 30)"),
                  1, 86400 * 365);
  whole_number_in(serve_cmd->add_option("--abandon-idle-s", serve.quotas.abandon_idle_s,
                                        "a live run with no viewer and no input for this long ends as abandoned "
                                        "(default 600)"),
                  1, 86400 * 365);
  whole_number_in(serve_cmd->add_option("--test-db-max-pages", serve.test_db_max_pages,
                                        "TESTS ONLY: cap the database file at this many pages (PRAGMA max_page_count) "
                                        "to simulate a full disk"),
                  1, std::int64_t(1) << 40)
      ->group("");  // hidden from --help
  whole_number_in(serve_cmd->add_option("--test-build-delay-ms", serve.test_build_delay_ms,
                                        "tests only: every request that builds scenarios waits this long on the "
                                        "builder pool"),
                  0, 600000)
      ->group("");  // hidden
  serve_cmd->add_flag("--test-db-read-only", serve.test_db_read_only,
                      "TESTS ONLY: refuse every write to the database (PRAGMA query_only), as a read-only file would")
      ->group("");
  serve_cmd->add_option("--allow-host", serve.allow_hosts,
                        "also accept requests whose Host names NAME (repeatable; e.g. behind a proxy or on --host 0.0.0.0)");
  serve_cmd->add_option("--allow-origin", serve.allow_origins,
                        "also accept changes and WebSockets from web pages of ORIGIN, e.g. http://lab.example:3000 "
                        "(repeatable; answers CORS for it)");
  serve_cmd->add_option("--token", serve.token,
                        "require Authorization: Bearer TOKEN for changes, WebSocket inputs and reads "
                        "(default: the RRLAB_TOKEN environment variable, which ps does not show)")
      ->envname("RRLAB_TOKEN");
  serve_cmd->add_flag("--public-read", serve.public_read, "with --token: reads and watching need no token");
  serve_cmd->add_flag("--allow-anonymous", serve.allow_anonymous,
                      "serve a non-loopback --host without a token (anyone who reaches it may drive it)");

  rrlab::cli::RunOptions run;
  CLI::App* run_cmd = app.add_subcommand("run", "simulate a scenario (or a run record) and print a JSON summary");
  run_cmd->add_option("scenario", run.scenario_file, "scenario JSON file, or a run record")->required();
  run_cmd->add_option("--method", run.method, "method name (overrides the scenario's)");
  run_cmd->add_option("--param", run.params, "method parameter NAME=VALUE (repeatable)");
  whole_number_in(run_cmd->add_option("--steps", run.steps, "number of steps (default: duration / dt)"), 1,
                  rrlab::ScenarioLimits::max_steps);
  run_cmd->add_option("--out", run.out_csv, "write one CSV row per step to this file");
  run_cmd->add_option("--db", run.db, "store the run and its frames in this SQLite database");

  rrlab::cli::ReplayOptions replay;
  CLI::App* replay_cmd = app.add_subcommand("replay", "re-simulate a stored run from its recorded inputs");
  whole_number_in(replay_cmd->add_option("run", replay.run_id, "run id")->required(), 1, kInt64Max);
  replay_cmd->add_option("--db", replay.db, "SQLite database file")->required();
  replay_cmd->add_flag("--verify", replay.verify, "exit 1 unless every frame equals the stored one bit for bit");

  app.add_subcommand("methods", "print every method with its parameter specs as JSON");

  std::string collisions_file;
  CLI::App* collisions_cmd =
      app.add_subcommand("collisions", "print a scenario robot's allowed-collision matrix (self-collision pairs) as JSON");
  collisions_cmd->add_option("scenario", collisions_file, "scenario JSON file")->required();

  rrlab::cli::SweepOptions sweep;
  CLI::App* sweep_cmd = app.add_subcommand("sweep", "run a sweep spec's runs (resumable, shardable) into a database");
  sweep_cmd->add_option("spec", sweep.spec_file, "sweep spec JSON file")->required();
  sweep_cmd->add_option("--db", sweep.db, "SQLite database file (created if missing)")->required();
  whole_number_in(sweep_cmd->add_option("--jobs", sweep.jobs, "worker threads (default: one per hardware thread)"), 1,
                  1024);
  sweep_cmd->add_option("--shard", sweep.shard, "run shard I of N (0-based): the runs whose position mod N is I");
  whole_number_in(sweep_cmd->add_option("--shards", sweep.shards,
                                        "N shards, this one's index from SLURM_ARRAY_TASK_ID or JOB_COMPLETION_INDEX"),
                  1, 1'000'000);
  sweep_cmd->add_option("--out", sweep.out_csv, "write the shard's run summaries as CSV to this file");
  sweep_cmd->add_flag("--frames", sweep.frames, "store every run's frames too (default: summaries only)");
  sweep_cmd->add_option("--scenarios", sweep.scenarios_dir, "directory of catalogue scenarios (NAME.json)");

  rrlab::cli::GenerateOptions generate;
  CLI::App* generate_cmd =
      app.add_subcommand("generate", "write a generated family's cases (with their witnesses) as scenario files");
  std::string family_names;
  for (const std::string& name : rrlab::generator_families()) family_names += (family_names.empty() ? "" : ", ") + name;
  generate_cmd->add_option("family", generate.family, family_names + " (or --perturb)");
  generate_cmd->add_flag("--list", generate.list, "print the families, one a line: name, a tab, what its cases are");
  generate_cmd->add_option("--perturb", generate.perturb,
                           "instead of a family: the perturbation family of this scenario (catalogue name or .json "
                           "path); --option obstacles.shift=M (or obstacles.shift_reach=F of the reach, capped at "
                           "obstacles.shift_gap=G of the free gap), obstacles.rotate_deg=D, speed=[MIN,MAX], "
                           "q0_self_motion=RAD, path.shift=M (or path.shift_reach=F, path.shift_gap=G)");
  generate_cmd->add_option("--scenarios", generate.scenarios_dir, "directory of catalogue scenarios (NAME.json)");
  // the seeds a sweep spec's entries take (sweep/sweep_spec.cpp): a file is a sweep's case
  whole_number_in(generate_cmd->add_option("--seed", generate.seed, "the family's seed (as a sweep entry's \"seed\")"),
                  0, kInt64Max);
  CLI::Option* count_option =
      whole_number_in(generate_cmd->add_option("--count", generate.count, "cases to write"), 1, 1'000'000);
  CLI::Option* first_option = whole_number_in(
      generate_cmd->add_option("--first", generate.first, "index of the first case (default 0)"), 0, 1'000'000'000);
  whole_number_in(generate_cmd->add_option("--cases", generate.cases,
                                           "exactly these case indices, comma-separated (a sweep report's unsolved "
                                           "cases), instead of --count and --first")
                      ->delimiter(','),
                  0, 1'000'000'000)
      ->excludes(count_option)
      ->excludes(first_option);
  generate_cmd->add_option("--option", generate.options, "family option KEY=VALUE, VALUE as JSON (repeatable)");
  generate_cmd->add_option("--out", generate.out_dir, "directory to write FAMILY-INDEX.json (NAME-pINDEX.json) files into");

  rrlab::cli::MergeOptions merge;
  CLI::App* merge_cmd = app.add_subcommand("merge", "merge shard databases' sweep runs into one database");
  merge_cmd->add_option("out", merge.out_db, "database to merge into (created if missing)")->required();
  merge_cmd->add_option("in", merge.in_dbs, "databases to merge from")->required();

  rrlab::cli::ReportOptions report;
  CLI::App* report_cmd = app.add_subcommand("report", "report a database's sweeps (markdown, HTML or CSV)");
  report_cmd->add_option("db", report.db, "SQLite database file")->required();
  report_cmd->add_option("--sweep", report.sweep, "only this sweep");
  report_cmd->add_option("--format", report.format, "md, html or csv")->check(CLI::IsMember({"md", "html", "csv"}));
  report_cmd->add_option("--out", report.out, "write to this file (default: stdout)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  if (serve_cmd->parsed()) return rrlab::cli::serve(serve);
  if (run_cmd->parsed()) return rrlab::cli::run(run);
  if (replay_cmd->parsed()) return rrlab::cli::replay(replay);
  if (sweep_cmd->parsed()) return rrlab::cli::sweep(sweep);
  if (merge_cmd->parsed()) return rrlab::cli::merge(merge);
  if (generate_cmd->parsed()) return rrlab::cli::generate(generate);
  if (report_cmd->parsed()) return rrlab::cli::report(report);
  if (collisions_cmd->parsed()) return rrlab::cli::collisions(collisions_file);
  return rrlab::cli::methods();
}
