// Subcommands of the rrlab executable.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace rrlab::cli {

struct RunOptions {
  std::string scenario_file;
  std::optional<std::string> method;
  std::vector<std::string> params;  // NAME=VALUE
  std::optional<long> steps;
  std::optional<std::string> out_csv;
};

// Exit codes: 0 run completed, 2 bad input (message on stderr).
int run(const RunOptions& options);
int methods();

}  // namespace rrlab::cli
