#include "fuzz_support.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <future>
#include <stdexcept>
#include <unistd.h>

#include <rrlab/methods/method.hpp>
#include <rrlab/scenario/scenario.hpp>
#include <rrlab/server/app/run_manager.hpp>
#include <rrlab/server/routes/routes.hpp>
#include <rrlab/server/routes/socket_message.hpp>
#include <rrlab/sim/run_inputs.hpp>
#include <rrlab/storage/frame_writer.hpp>
#include <rrlab/storage/run_store.hpp>

namespace rrlab::fuzz {

using nlohmann::json;

std::string as_text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

[[noreturn]] static void finding(const std::string& what, const std::string& detail) {
  std::fprintf(stderr, "\nFINDING in %s: %s\n", what.c_str(), detail.c_str());
  std::fflush(stderr);
  std::abort();
}

void expect_documented(const std::string& what, const std::function<void()>& parse) {
  try {
    parse();
  } catch (const ScenarioError&) {
  } catch (const ParamError&) {
  } catch (const InputStateError&) {
  } catch (const server::DomainError&) {
  } catch (const nlohmann::json::parse_error&) {
  } catch (const std::exception& e) {
    finding(what, std::string("undocumented exception: ") + e.what());
  } catch (...) {
    finding(what, "a non-standard exception");
  }
}

struct Server::State {
  std::filesystem::path dir;
  std::unique_ptr<storage::RunStore> idle_store, live_store;
  std::unique_ptr<storage::FrameWriter> idle_writer, live_writer;
  std::unique_ptr<server::RunManager> idle, live;
  server::ServerInfo info{"fuzz", std::chrono::steady_clock::now()};
  std::shared_ptr<server::RunGroup> group;
  std::shared_ptr<server::FrameSource> source;
  std::int64_t run_id = 0;
  int lane = 0;
  long inputs = 0;
};

Server& Server::get() {
  static Server* server = new Server();  // never destroyed: its run thread lives until exit
  return *server;
}

Server::Server() : state_(std::make_unique<State>()) {
  std::string pattern = (std::filesystem::temp_directory_path() / "rrlab-fuzz-XXXXXX").string();
  if (!mkdtemp(pattern.data())) finding("setup", "mkdtemp failed");
  State& s = *state_;
  s.dir = pattern;
  const std::string scenarios = std::string(RRLAB_SOURCE_DIR) + "/scenarios";
  s.idle_store = std::make_unique<storage::RunStore>((s.dir / "idle.db").string());
  s.idle_writer = std::make_unique<storage::FrameWriter>(*s.idle_store);
  server::ServerLimits refuse;
  refuse.max_active_runs = 0;  // every run, comparison and sweep is parsed, then refused (503)
  s.idle = std::make_unique<server::RunManager>(*s.idle_store, *s.idle_writer, scenarios, refuse);
  s.live_store = std::make_unique<storage::RunStore>((s.dir / "live.db").string());
  s.live_writer = std::make_unique<storage::FrameWriter>(*s.live_store);
  s.live = std::make_unique<server::RunManager>(*s.live_store, *s.live_writer, scenarios);
  fresh_run();
}

// A new paused live run of the joystick scenario (obstacles, joystick and
// parameters all apply to it).
void Server::fresh_run() {
  State& s = *state_;
  if (s.group) {
    s.group->request_stop();
    s.group->wait_exited();
  }
  server::ApiRequest request{"POST", "/api/runs", {}, R"({"scenario": "04_planar7_joystick", "paused": true})",
                             "application/json", "", ""};
  const server::ApiResponse response = server::handle_api(*s.live, s.info, request);
  if (response.status != 201) finding("setup", "starting the live run: " + response.body);
  s.run_id = json::parse(response.body).at("id").get<std::int64_t>();
  s.group = s.live->group_of(s.run_id, s.lane);
  s.source = s.group->source(s.lane);
}

// Back to a paused run: paused again if an input started it, a fresh run if
// it stopped, and every 256 inputs (inputs accumulate: obstacles, parameters).
void Server::after_input() {
  State& s = *state_;
  const std::string status = s.group->status_json(s.lane).at("status").get<std::string>();
  if (status == "running") {
    try {
      s.group->control(s.lane, {server::ControlAction::pause, std::nullopt});
      if (++s.inputs % 256 != 0) return;
    } catch (const server::DomainError&) {
    }
  } else if (status == "paused" && ++s.inputs % 256 != 0) {
    return;
  }
  fresh_run();
}

static void check(const std::string& what, const server::ApiResponse& response) {
  if (response.status >= 500 && response.status != 503) finding(what, std::to_string(response.status) + " " + response.body);
}

server::ApiResponse Server::idle_call(const std::string& method, const std::string& path, const std::string& body) {
  server::ApiRequest request{method, path, {}, body, "application/json", "", ""};
  server::ApiResponse response = server::handle_api(*state_->idle, state_->info, request);
  check(method + " " + path, response);
  return response;
}

server::ApiResponse Server::live_call(const std::string& method, const std::string& path_after_run,
                                      const std::string& body) {
  const std::string path = "/api/runs/" + std::to_string(state_->run_id) + path_after_run;
  server::ApiRequest request{method, path, {}, body, "application/json", "", ""};
  server::ApiResponse response = server::handle_api(*state_->live, state_->info, request);
  if (response.deferred) {  // an input once stored, a step once taken, a stop once the run ended
    auto answered = std::make_shared<std::promise<server::ApiResponse>>();
    std::future<server::ApiResponse> answer = answered->get_future();
    response.deferred([answered](server::ApiResponse ready) { answered->set_value(std::move(ready)); });
    if (answer.wait_for(std::chrono::seconds(30)) != std::future_status::ready)
      finding(method + " " + path, "no answer within 30 s");
    response = answer.get();
  }
  check(method + " " + path, response);
  after_input();
  return response;
}

json Server::live_message(const std::string& text) {
  const server::MessageReply message = server::reply_to_socket_message(*state_->source, "fuzz", true, text);
  json reply = message.reply;
  if (message.pending) {  // the ack of an input once stored, of a step once taken
    auto settled = std::make_shared<std::promise<storage::Outcome>>();
    std::future<storage::Outcome> outcome = settled->get_future();
    message.pending->then([settled](const storage::Outcome& o) { settled->set_value(o); });
    if (outcome.wait_for(std::chrono::seconds(30)) != std::future_status::ready)
      finding("WebSocket message", "no ack within 30 s");
    reply = server::settled_reply(message.reply, outcome.get());
  }
  if (reply.value("type", "") == "error" && reply.at("error").value("code", "") == "internal")
    finding("WebSocket message", reply.dump());
  after_input();
  return reply;
}

}  // namespace rrlab::fuzz
