// Integer options of every subcommand (cli/whole_number.hpp): a negative, a
// huge or a non-number value exits 2 naming the option and its range, before
// the command does anything; a leading zero is decimal, not octal.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <sstream>

#include "rrlab_command.hpp"

namespace {

using rrlab::testing::run_cli;

struct BadNumber {
  std::string name, args, option, range, given;
};

class CliBadNumber : public ::testing::TestWithParam<BadNumber> {};

TEST_P(CliBadNumber, ExitsTwoNamingTheOptionAndItsRange) {
  const BadNumber& c = GetParam();
  const rrlab::testing::CliRun r = run_cli(c.args);
  EXPECT_EQ(r.code, 2) << r.err;
  const std::string expected = c.option + ": must be a whole number in " + c.range + ", got '" + c.given + "'";
  EXPECT_NE(r.err.find(expected), std::string::npos) << "expected: " << expected << "\nstderr: " << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

const std::string kOut = " --out " + (std::filesystem::temp_directory_path() / "rrlab_bad_number").string();
const std::string kScenario = std::string(RRLAB_SOURCE_DIR) + "/scenarios/01_planar7_obstacles.json";
const std::string kSeeds = "[0, 9223372036854775807]";
// serve exits 2 on this origin right after parsing: a number the check let
// through fails the test at once instead of serving
const std::string kServe = "serve --allow-origin not-an-origin ";

BadNumber serve_case(const std::string& name, const std::string& option, const std::string& range,
                     const std::string& value = "-1") {
  return {name, kServe + option + " " + value, option, range, value};
}

INSTANTIATE_TEST_SUITE_P(
    Cases, CliBadNumber,
    ::testing::Values(
        BadNumber{"seed_negative", "generate planar_clutter --seed -1" + kOut, "--seed", kSeeds, "-1"},
        BadNumber{"seed_above_int64", "generate planar_clutter --seed 9223372036854775808" + kOut, "--seed", kSeeds,
                  "9223372036854775808"},
        BadNumber{"seed_uint64_max", "generate planar_clutter --seed 18446744073709551615" + kOut, "--seed", kSeeds,
                  "18446744073709551615"},
        BadNumber{"seed_word", "generate planar_clutter --seed one" + kOut, "--seed", kSeeds, "one"},
        BadNumber{"seed_hex", "generate planar_clutter --seed 0x10" + kOut, "--seed", kSeeds, "0x10"},
        BadNumber{"seed_plus", "generate planar_clutter --seed=+3" + kOut, "--seed", kSeeds, "+3"},
        BadNumber{"count_negative", "generate planar_clutter --count -1" + kOut, "--count", "[1, 1000000]", "-1"},
        BadNumber{"count_zero", "generate planar_clutter --count 0" + kOut, "--count", "[1, 1000000]", "0"},
        BadNumber{"count_past_int", "generate planar_clutter --count 4294967297" + kOut, "--count", "[1, 1000000]",
                  "4294967297"},
        BadNumber{"count_fraction", "generate planar_clutter --count 2.5" + kOut, "--count", "[1, 1000000]", "2.5"},
        BadNumber{"first_negative", "generate planar_clutter --first -1" + kOut, "--first", "[0, 1000000000]", "-1"},
        BadNumber{"first_exponent", "generate planar_clutter --first 1e3" + kOut, "--first", "[0, 1000000000]", "1e3"},
        BadNumber{"first_huge", "generate planar_clutter --first 99999999999999999999999" + kOut, "--first",
                  "[0, 1000000000]", "99999999999999999999999"},
        BadNumber{"perturb_seed", "generate --perturb 22_kapoor_square_circle --seed -2" + kOut, "--seed", kSeeds,
                  "-2"},
        BadNumber{"steps_negative", "run " + kScenario + " --steps -1", "--steps", "[1, 10000000]", "-1"},
        BadNumber{"steps_huge", "run " + kScenario + " --steps 18446744073709551616", "--steps", "[1, 10000000]",
                  "18446744073709551616"},
        BadNumber{"steps_word", "run " + kScenario + " --steps ten", "--steps", "[1, 10000000]", "ten"},
        BadNumber{"replay_negative", "replay -1 --db /nonexistent.db", "run", "[1, 9223372036854775807]", "-1"},
        BadNumber{"replay_huge", "replay 9223372036854775808 --db /nonexistent.db", "run", "[1, 9223372036854775807]",
                  "9223372036854775808"},
        BadNumber{"replay_word", "replay last --db /nonexistent.db", "run", "[1, 9223372036854775807]", "last"},
        BadNumber{"jobs_negative", "sweep spec.json --db /nonexistent/x.db --jobs -1", "--jobs", "[1, 1024]", "-1"},
        BadNumber{"jobs_huge", "sweep spec.json --db /nonexistent/x.db --jobs 4294967296", "--jobs", "[1, 1024]",
                  "4294967296"},
        BadNumber{"shards_negative", "sweep spec.json --db /nonexistent/x.db --shards -3", "--shards", "[1, 1000000]",
                  "-3"},
        serve_case("port_negative", "--port", "[0, 65535]"),
        serve_case("port_past_short", "--port", "[0, 65535]", "65536"),
        serve_case("threads", "--threads", "[1, 64]", "0"),
        serve_case("body_limit", "--body-limit", "[1024, 67108864]"),
        serve_case("ws_stall_ms", "--ws-stall-ms", "[100, 600000]", "2147483648"),
        serve_case("export_memory", "--export-memory", "[131072, 1099511627776]"),
        serve_case("connections_per_address", "--connections-per-address", "[4, 65536]"),
        serve_case("max_websockets", "--max-websockets", "[16, 65536]"),
        serve_case("websockets_per_address", "--websockets-per-address", "[1, 65536]"),
        serve_case("websockets_per_client", "--websockets-per-client", "[1, 65536]", "many"),
        serve_case("max_run_frames", "--max-run-frames", "[1, 100000000]"),
        serve_case("max_run_bytes", "--max-run-bytes", "[1, 1125899906842624]"),
        serve_case("max_total_bytes", "--max-total-bytes", "[1, 1152921504606846976]", "18446744073709551615"),
        serve_case("max_scenarios", "--max-scenarios", "[0, 1000000]"),
        serve_case("test_db_max_pages", "--test-db-max-pages", "[1, 1099511627776]"),
        serve_case("test_build_delay_ms", "--test-build-delay-ms", "[0, 600000]")),
    [](const ::testing::TestParamInfo<BadNumber>& info) { return info.param.name; });

// Every integer option (CLI11 shows its type as INT or UINT in --help) carries
// the check, which --help shows as its range: an option added without it fails here.
TEST(CliNumbers, EveryIntegerOptionOfEverySubcommandShowsItsRange) {
  const std::regex integer_option(R"(^\s+(-[-\w]+|\w+)\s+U?INT\b(:in \[-?\d+, \d+\])?)");
  int seen = 0;
  for (const char* command : {"serve", "run", "replay", "methods", "sweep", "generate", "merge", "report"}) {
    const rrlab::testing::CliRun help = run_cli(std::string(command) + " --help");
    ASSERT_EQ(help.code, 0) << command << ": " << help.err;
    std::istringstream lines(help.out);
    for (std::string line; std::getline(lines, line);) {
      std::smatch match;
      if (!std::regex_search(line, match, integer_option)) continue;
      ++seen;
      EXPECT_TRUE(match[2].matched) << command << " " << match[1] << ": no range in '" << line << "'";
    }
  }
  EXPECT_GE(seen, 20);  // serve 13 (and 2 hidden, tested above), run 1, replay 1, sweep 2, generate 3
}

TEST(CliNumbers, BoundsAreAcceptedAndALeadingZeroIsDecimal) {
  const auto dir = std::filesystem::temp_directory_path() / "rrlab_cli_numbers_test";
  std::filesystem::remove_all(dir);
  const rrlab::testing::CliRun made =
      run_cli("generate planar_clutter --seed 9223372036854775807 --count 1 --first 010 --out " + dir.string());
  ASSERT_EQ(made.code, 0) << made.err;
  EXPECT_NE(made.out.find("planar_clutter-10.json"), std::string::npos) << made.out;  // 010 is ten, not octal eight
  std::filesystem::remove_all(dir);
}

}  // namespace
