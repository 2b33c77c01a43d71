// Runs the rrlab executable (RRLAB_BINARY) with arguments, capturing its exit
// code, stdout and stderr: for the command-line tests of every module.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace rrlab::testing {

struct CliRun {
  int code = -1;
  std::string out, err;
};

inline CliRun run_cli(const std::string& args) {
  const std::string err_file =
      std::filesystem::temp_directory_path() / ("rrlab_err_" + std::to_string(::getpid()));
  const std::string cmd = std::string(RRLAB_BINARY) + " " + args + " 2>" + err_file;
  CliRun r;
  FILE* pipe = ::popen(cmd.c_str(), "r");
  std::array<char, 4096> buf{};
  size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) r.out.append(buf.data(), n);
  const int status = ::pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(err_file);
  std::stringstream ss;
  ss << in.rdbuf();
  r.err = ss.str();
  std::filesystem::remove(err_file);
  return r;
}

}  // namespace rrlab::testing
