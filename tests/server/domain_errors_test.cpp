// The app's domain errors and the routes' table from Problem to HTTP status;
// the server's enums and their names (one to_string and one parse each).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <rrlab/server/api/errors.hpp>
#include <rrlab/server/app/run_types.hpp>
#include <rrlab/server/routes/http_errors.hpp>
#include <rrlab/sim/run_inputs.hpp>

namespace rrlab::server {
namespace {

using nlohmann::json;

TEST(DomainErrors, EveryProblemHasItsStatus) {
  const std::pair<Problem, int> expected[] = {
      {Problem::invalid, 400},      {Problem::unauthorized, 401},     {Problem::not_found, 404},
      {Problem::not_allowed, 405},  {Problem::conflict, 409},         {Problem::too_large, 413},
      {Problem::unprocessable, 422}, {Problem::too_many, 429},        {Problem::busy, 503},
      {Problem::unavailable, 503},  {Problem::storage_full, 503},     {Problem::storage_readonly, 503},
      {Problem::quota, 507},        {Problem::storage, 500},          {Problem::internal, 500}};
  for (const auto& [problem, status] : expected) EXPECT_EQ(http_status(problem), status) << int(problem);
}

TEST(DomainErrors, AnswerKeepsCodeMessagePathAndDetail) {
  const DomainError error(Problem::too_large, "run_too_large", "too many", "steps",
                          {{"limit", "max_run_frames"}, {"code", "never over the code"}});
  const ApiResponse response = error_response(error);
  EXPECT_EQ(response.status, 413);
  const json body = json::parse(response.body).at("error");
  EXPECT_EQ(body["code"], "run_too_large");
  EXPECT_EQ(body["message"], "too many");
  EXPECT_EQ(body["path"], "steps");
  EXPECT_EQ(body["limit"], "max_run_frames");
  const json socket = socket_error(error);
  EXPECT_EQ(socket["type"], "error");
  EXPECT_EQ(socket["error"], body);  // the same error object, without a status
}

TEST(DomainErrors, UnderPrefixesThePath) {
  const DomainError bare(Problem::conflict, "wrong_state", "the run has ended");
  EXPECT_EQ(bare.under("payload").path(), "payload");
  const DomainError field(Problem::invalid, "invalid", "no obstacle", "id");
  const DomainError moved = field.under("payload");
  EXPECT_EQ(moved.path(), "payload.id");
  EXPECT_EQ(moved.problem(), Problem::invalid);
  EXPECT_EQ(moved.code(), "invalid");
  EXPECT_STREQ(moved.what(), "no obstacle");
}

TEST(DomainErrors, EngineErrorsMapToProblems) {
  const auto mapped = [](auto thrown, Problem validation = Problem::invalid) {
    try {
      try {
        throw thrown;
      } catch (...) {
        rethrow_as_domain_error("payload", validation);
      }
    } catch (const DomainError& e) {
      return e;
    }
    return DomainError(Problem::internal, "none", "");
  };
  const DomainError scenario = mapped(ScenarioError("dt", "must be positive"), Problem::unprocessable);
  EXPECT_EQ(scenario.problem(), Problem::unprocessable);
  EXPECT_EQ(scenario.code(), "invalid");
  EXPECT_EQ(scenario.path(), "payload.dt");
  const DomainError state = mapped(InputStateError("not a joystick"));
  EXPECT_EQ(state.problem(), Problem::conflict);
  EXPECT_EQ(state.code(), "wrong_state");
  EXPECT_EQ(state.path(), "payload");
  EXPECT_EQ(mapped(std::runtime_error("boom")).problem(), Problem::internal);
}

template <typename Enum, typename Parse>
void round_trip(std::initializer_list<Enum> values, Parse parse) {
  for (const Enum value : values) {
    const auto parsed = parse(to_string(value));
    ASSERT_TRUE(parsed.has_value()) << to_string(value);
    EXPECT_EQ(*parsed, value);
  }
  EXPECT_FALSE(parse("nonsense").has_value());
}

TEST(ServerEnums, NamesRoundTrip) {
  round_trip({RunMode::live, RunMode::batch, RunMode::resimulation}, parse_run_mode);
  round_trip({RunStatus::running, RunStatus::paused, RunStatus::stopping, RunStatus::stopped, RunStatus::completed,
              RunStatus::failed, RunStatus::interrupted},
             parse_run_status);
  round_trip({ControlAction::start, ControlAction::pause, ControlAction::step, ControlAction::reset,
              ControlAction::stop},
             parse_control_action);
  round_trip({ReplayAction::play, ReplayAction::pause, ReplayAction::seek}, parse_replay_action);
  round_trip({InputKind::params, InputKind::obstacle, InputKind::obstacle_add, InputKind::obstacle_remove,
              InputKind::joystick, InputKind::method, InputKind::reset},
             parse_input_kind);
  EXPECT_STREQ(to_string(RunMode::live), "live");
  EXPECT_STREQ(to_string(RunStatus::completed), "completed");
  EXPECT_STREQ(to_string(SweepStatus::stopped), "stopped");
}

}  // namespace
}  // namespace rrlab::server
