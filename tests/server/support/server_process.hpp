// Starts a real `rrlab serve` on an ephemeral port with a temporary database
// and stops it (SIGTERM, or SIGKILL for crash tests).
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace rrlab::testing {

class ServerProcess {
 public:
  // `db` empty: a new temporary file. Extra arguments go after `serve`'s own
  // (--scenarios among them replaces the source tree's scenarios/).
  explicit ServerProcess(std::string db = "", std::vector<std::string> extra_args = {});
  ~ServerProcess();
  ServerProcess(const ServerProcess&) = delete;
  ServerProcess& operator=(const ServerProcess&) = delete;

  unsigned short port() const { return port_; }
  const std::string& db() const { return db_; }
  void kill_hard();       // SIGKILL, as a crash
  int stop();             // SIGTERM and wait; the exit status
  bool running() const { return pid_ > 0; }
  pid_t pid() const { return pid_; }

 private:
  pid_t pid_ = -1;
  unsigned short port_ = 0;
  std::string db_, dir_;
};

// Runs the rrlab binary with arguments; returns its exit code and stdout.
struct CommandResult {
  int exit_code = -1;
  std::string out;
};
CommandResult run_rrlab(const std::vector<std::string>& args);

std::string temp_dir();  // a fresh directory under /tmp

// A process's resident memory (VmRSS of /proc/PID/status) in KiB; -1 if unknown.
long resident_kib(pid_t pid);

}  // namespace rrlab::testing
