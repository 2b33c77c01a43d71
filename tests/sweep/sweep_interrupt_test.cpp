// `rrlab sweep` in a child process, interrupted with SIGINT and run again:
// the union equals an uninterrupted sweep's runs, with no key twice.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>

#include <chrono>

#include "support/eventually.hpp"
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
  rrlab::test::eventually(
      [&] {
        if (!std::filesystem::exists(db)) return false;
        try {
          storage::RunStore store(db);
          stored_at_signal = store.sweep_keys("interrupted").size();
          return stored_at_signal >= 10;
        } catch (const std::exception&) {  // the child may still be creating it
          return false;
        }
      },
      std::chrono::seconds(60), "10 runs stored by the sweep");
  ::kill(pid, SIGINT);
  int status = 0;
  // runs stop between two steps: the child exits at once; 60 s at most, then it is killed and reported
  if (!rrlab::test::eventually([&] { return ::waitpid(pid, &status, WNOHANG) != 0; }, std::chrono::seconds(60),
                               "rrlab sweep to exit after SIGINT")) {
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
    return -1;
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
