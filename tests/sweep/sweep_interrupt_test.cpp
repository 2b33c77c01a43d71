// `rrlab sweep` in a child process, interrupted with SIGINT and run again:
// the union equals an uninterrupted sweep's runs, with no key twice.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>

#include <chrono>
#include <thread>

#include "sweep_test_support.hpp"

extern char** environ;

namespace rrlab::sweep {
namespace {

// 2 scenarios × 3 configurations × 150 seeds: long enough to interrupt.
std::string write_spec(const testing::TempDir& dir) {
  nlohmann::json spec = testing::small_spec("interrupted");
  spec["steps"] = 400;
  spec["seeds"] = nlohmann::json::array();
  for (int s = 0; s < 150; ++s) spec["seeds"].push_back(s);
  return dir.write("spec.json", spec.dump());
}

int run_child_interrupted(const std::string& spec, const std::string& db, size_t& stored_at_signal) {
  const std::string binary = RRLAB_BINARY;
  std::vector<std::string> args = {binary, "sweep", spec, "--db", db, "--jobs", "2"};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  if (posix_spawn(&pid, binary.c_str(), &actions, nullptr, argv.data(), environ) != 0) return -1;
  posix_spawn_file_actions_destroy(&actions);
  // wait for some runs, then interrupt
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    if (!std::filesystem::exists(db)) continue;
    try {
      storage::RunStore store(db);
      stored_at_signal = store.sweep_keys("interrupted").size();
      if (stored_at_signal >= 10) break;
    } catch (const std::exception&) {  // the child may still be creating it
    }
  }
  ::kill(pid, SIGINT);
  int status = 0;
  // runs stop between two steps: the child exits at once; 60 s at most, then it is killed and reported
  const auto exit_deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (::waitpid(pid, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > exit_deadline) {
      ADD_FAILURE() << "rrlab sweep did not exit within 60 s of SIGINT";
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      return -1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(SweepInterrupt, SigintStopsCleanlyAndARerunCompletesTheSweep) {
  testing::TempDir dir;
  const std::string spec = write_spec(dir);
  const size_t total = 2 * 3 * 150;

  size_t stored_at_signal = 0;
  const int code = run_child_interrupted(spec, dir.file("interrupted.db"), stored_at_signal);
  EXPECT_EQ(code, 130) << "the sweep ended before SIGINT reached it";
  {
    storage::RunStore store(dir.file("interrupted.db"));
    const size_t stored = store.sweep_keys("interrupted").size();
    EXPECT_GE(stored, stored_at_signal);
    EXPECT_LT(stored, total);
    EXPECT_EQ(store.runs({.limit = 100000}).size(), stored);  // nothing half-stored: every run has its key
  }
  const testing::CommandResult again = testing::rrlab("sweep " + spec + " --db " + dir.file("interrupted.db") + " --jobs 2");
  ASSERT_EQ(again.code, 0) << again.err;
  const testing::CommandResult whole = testing::rrlab("sweep " + spec + " --db " + dir.file("whole.db") + " --jobs 2");
  ASSERT_EQ(whole.code, 0) << whole.err;

  storage::RunStore resumed(dir.file("interrupted.db")), uninterrupted(dir.file("whole.db"));
  EXPECT_EQ(resumed.sweep_keys("interrupted").size(), total);
  EXPECT_EQ(resumed.runs({.limit = 100000}).size(), total);  // no duplicate runs
  EXPECT_EQ(testing::stored_runs(resumed, "interrupted"), testing::stored_runs(uninterrupted, "interrupted"));
}

}  // namespace
}  // namespace rrlab::sweep
