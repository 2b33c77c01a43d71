#include "server_process.hpp"

#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <stdexcept>
#include <thread>

#include "support/poll_until.hpp"

namespace rrlab::testing {

std::string temp_dir() {
  std::string pattern = "/tmp/rrlab-test-XXXXXX";
  if (!mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
  return pattern;
}

ServerProcess::ServerProcess(std::string db, std::vector<std::string> extra_args) : db_(std::move(db)) {
  if (db_.empty()) {
    dir_ = temp_dir();
    db_ = dir_ + "/rrlab.db";
  }
  int out[2];
  if (pipe(out) != 0) throw std::runtime_error("pipe failed");
  std::vector<std::string> args = {RRLAB_BINARY, "serve", "--port", "0", "--db", db_,
                                   "--web", std::string(RRLAB_SOURCE_DIR) + "/web"};
  // the source tree's scenarios/, unless the extra arguments name another directory
  if (std::find(extra_args.begin(), extra_args.end(), "--scenarios") == extra_args.end())
    args.insert(args.end(), {"--scenarios", std::string(RRLAB_SOURCE_DIR) + "/scenarios"});
  args.insert(args.end(), extra_args.begin(), extra_args.end());
  const pid_t parent = getpid();
  pid_ = fork();
  if (pid_ == 0) {
    // the server ends with the test process, however that ends (ctest's timeout kills the test)
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) _exit(127);
    dup2(out[1], STDOUT_FILENO);
    close(out[0]);
    close(out[1]);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  close(out[1]);
  // the first line names the port: "rrlab: serving http://127.0.0.1:PORT/ ..."; 60 s at most
  std::string line;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    pollfd ready{out[0], POLLIN, 0};
    char c = 0;
    if (left.count() <= 0 || poll(&ready, 1, int(left.count())) <= 0 || read(out[0], &c, 1) != 1 || c == '\n') break;
    line += c;
  }
  // keep draining stdout so the server never blocks on a full pipe
  std::thread([fd = out[0]] {
    char buf[4096];
    while (read(fd, buf, sizeof buf) > 0) {
    }
    close(fd);
  }).detach();
  const auto colon = line.rfind(':');
  if (line.rfind("rrlab: serving", 0) != 0 || colon == std::string::npos) {
    kill_hard();  // the destructor does not run for a constructor that throws
    if (!dir_.empty()) std::system(("rm -rf '" + dir_ + "'").c_str());
    throw std::runtime_error("rrlab serve did not print its address within 60 s: \"" + line + "\"");
  }
  port_ = static_cast<unsigned short>(std::stoi(line.substr(colon + 1)));
}

ServerProcess::~ServerProcess() {
  if (pid_ > 0) stop();
  if (!dir_.empty()) std::system(("rm -rf '" + dir_ + "'").c_str());
}

void ServerProcess::kill_hard() {
  if (pid_ <= 0) return;
  ::kill(pid_, SIGKILL);
  int status = 0;
  waitpid(pid_, &status, 0);
  pid_ = -1;
}

int ServerProcess::stop() {
  if (pid_ <= 0) return -1;
  ::kill(pid_, SIGTERM);
  int status = 0;
  // 60 s for a clean stop, then SIGKILL: a hung shutdown is reported, not waited for until ctest's timeout
  if (!rrlab::test::poll_until([&] { return waitpid(pid_, &status, WNOHANG) != 0; }, std::chrono::seconds(60))) {
    std::fprintf(stderr, "rrlab serve (pid %d) did not stop within 60 s of SIGTERM: killed\n", int(pid_));
    ::kill(pid_, SIGKILL);
    waitpid(pid_, &status, 0);
    pid_ = -1;
    return -1;
  }
  pid_ = -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

long resident_kib(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  return -1;
}

CommandResult run_rrlab(const std::vector<std::string>& args) {
  std::string command = RRLAB_BINARY;
  for (const auto& a : args) command += " '" + a + "'";
  command += " 2>/dev/null";
  CommandResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buf{};
  size_t n = 0;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) result.out.append(buf.data(), n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

}  // namespace rrlab::testing
