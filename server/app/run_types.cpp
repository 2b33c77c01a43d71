#include <rrlab/server/app/run_types.hpp>

#include <array>
#include <cstddef>

namespace rrlab::server {

namespace {

// Each enum's names, in the enum's order.
constexpr std::array<const char*, 3> kRunModeNames = {"live", "batch", "resimulation"};
constexpr std::array<const char*, 7> kRunStatusNames = {"running", "paused",  "stopping",   "stopped",
                                                        "completed", "failed", "interrupted"};
constexpr std::array<const char*, 5> kControlActionNames = {"start", "pause", "step", "reset", "stop"};
constexpr std::array<const char*, 3> kReplayActionNames = {"play", "pause", "seek"};
constexpr std::array<const char*, 4> kSweepStatusNames = {"running", "completed", "stopped", "failed"};

template <typename Enum, std::size_t N>
std::optional<Enum> enum_named(const std::array<const char*, N>& names, std::string_view text) {
  for (std::size_t i = 0; i < N; ++i)
    if (text == names[i]) return Enum(i);
  return std::nullopt;
}

}  // namespace

const char* to_string(RunMode mode) { return kRunModeNames.at(std::size_t(mode)); }
std::optional<RunMode> parse_run_mode(std::string_view text) { return enum_named<RunMode>(kRunModeNames, text); }

const char* to_string(RunStatus status) { return kRunStatusNames.at(std::size_t(status)); }
std::optional<RunStatus> parse_run_status(std::string_view text) {
  return enum_named<RunStatus>(kRunStatusNames, text);
}

const char* to_string(ControlAction action) { return kControlActionNames.at(std::size_t(action)); }
std::optional<ControlAction> parse_control_action(std::string_view text) {
  return enum_named<ControlAction>(kControlActionNames, text);
}

const char* to_string(ReplayAction action) { return kReplayActionNames.at(std::size_t(action)); }
std::optional<ReplayAction> parse_replay_action(std::string_view text) {
  return enum_named<ReplayAction>(kReplayActionNames, text);
}

const char* to_string(SweepStatus status) { return kSweepStatusNames.at(std::size_t(status)); }

}  // namespace rrlab::server
