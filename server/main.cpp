// rrlab: command line front end of the engine (run, methods).
#include <CLI/CLI.hpp>

#include "cli.hpp"

int main(int argc, char** argv) {
  CLI::App app{"rrlab: redundancy-resolution lab"};
  app.require_subcommand(1);

  rrlab::cli::RunOptions run;
  CLI::App* run_cmd = app.add_subcommand("run", "simulate a scenario and print a JSON summary");
  run_cmd->add_option("scenario", run.scenario_file, "scenario JSON file")->required();
  run_cmd->add_option("--method", run.method, "method name (overrides the scenario's)");
  run_cmd->add_option("--param", run.params, "method parameter NAME=VALUE (repeatable)");
  run_cmd->add_option("--steps", run.steps, "number of steps (default: duration / dt)");
  run_cmd->add_option("--out", run.out_csv, "write one CSV row per step to this file");

  app.add_subcommand("methods", "print every method with its parameter specs as JSON");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  if (run_cmd->parsed()) return rrlab::cli::run(run);
  return rrlab::cli::methods();
}
