// rrlab: command line front end (serve, run, replay, methods).
#include <CLI/CLI.hpp>

#include "cli.hpp"

int main(int argc, char** argv) {
  CLI::App app{"rrlab: redundancy-resolution lab"};
  app.require_subcommand(1);

  rrlab::cli::ServeOptions serve;
  CLI::App* serve_cmd = app.add_subcommand("serve", "serve the dashboard, REST and WebSocket API");
  serve_cmd->add_option("--host", serve.host, "address to bind (default 127.0.0.1: this machine only)");
  serve_cmd->add_option("--port", serve.port, "port (0: any free port, printed at start)");
  serve_cmd->add_option("--db", serve.db, "SQLite database file (created if missing)");
  serve_cmd->add_option("--web", serve.web_dir, "directory of the dashboard's static files");
  serve_cmd->add_option("--scenarios", serve.scenarios_dir, "directory of scenario files");
  serve_cmd->add_option("--threads", serve.threads, "I/O threads")->check(CLI::Range(1, 64));
  serve_cmd->add_option("--display-hz", serve.display_hz, "WebSocket frame rate")->check(CLI::Range(1.0, 240.0));
  serve_cmd->add_option("--body-limit", serve.body_limit, "largest request body in bytes")
      ->check(CLI::Range(std::size_t(1024), std::size_t(64) << 20));
  serve_cmd->add_option("--ws-stall-ms", serve.ws_stall_ms, "drop a WebSocket client whose write is stuck this long")
      ->check(CLI::Range(100, 600000));

  rrlab::cli::RunOptions run;
  CLI::App* run_cmd = app.add_subcommand("run", "simulate a scenario (or a run record) and print a JSON summary");
  run_cmd->add_option("scenario", run.scenario_file, "scenario JSON file, or a run record")->required();
  run_cmd->add_option("--method", run.method, "method name (overrides the scenario's)");
  run_cmd->add_option("--param", run.params, "method parameter NAME=VALUE (repeatable)");
  run_cmd->add_option("--steps", run.steps, "number of steps (default: duration / dt)");
  run_cmd->add_option("--out", run.out_csv, "write one CSV row per step to this file");
  run_cmd->add_option("--db", run.db, "store the run and its frames in this SQLite database");

  rrlab::cli::ReplayOptions replay;
  CLI::App* replay_cmd = app.add_subcommand("replay", "re-simulate a stored run from its recorded inputs");
  replay_cmd->add_option("run", replay.run_id, "run id")->required();
  replay_cmd->add_option("--db", replay.db, "SQLite database file")->required();
  replay_cmd->add_flag("--verify", replay.verify, "exit 1 unless every frame equals the stored one bit for bit");

  app.add_subcommand("methods", "print every method with its parameter specs as JSON");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  if (serve_cmd->parsed()) return rrlab::cli::serve(serve);
  if (run_cmd->parsed()) return rrlab::cli::run(run);
  if (replay_cmd->parsed()) return rrlab::cli::replay(replay);
  return rrlab::cli::methods();
}
