// Load against a real `rrlab serve` on loopback, bounded in time:
//  - 50 WebSocket clients on one live run at 60 Hz: delivered frames per
//    second per client, and latency from publication (right after the step)
//    to receipt, p50/p99;
//  - 100 concurrent batch runs over REST: all complete and all are stored;
//  - 20 clients steering 20 live runs (parameter changes and obstacle drags
//    at 50 Hz each, while the runs store 1,000 frames/s each): input → ack
//    latency p50/p99.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

#include "client.hpp"
#include "server_process.hpp"

namespace rrlab::testing {
namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

std::int64_t wall_now_us() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

void BM_WebSocketFanout50(benchmark::State& state) {
  const int clients = int(state.range(0));
  const auto window = std::chrono::seconds(5);
  ServerProcess server;
  // the demo scenario lasts 8 s; make it long enough for the window
  json scenario = json::parse(http(server.port(), "GET", "/api/scenarios/01_planar7_obstacles").body);
  scenario["duration"] = 600;
  double min_fps = 1e9, mean_fps = 0, p50 = 0, p90 = 0, p99 = 0, max_latency = 0, steps_per_s = 0;
  for (auto _ : state) {
    const json started =
        http_json(server.port(), "POST", "/api/runs", {{"scenario", scenario}, {"rate", 1}}).json();
    const std::string id = std::to_string(started["id"].get<long>());
    std::vector<std::unique_ptr<WsClient>> sockets;
    for (int i = 0; i < clients; ++i) sockets.push_back(std::make_unique<WsClient>(server.port(), "/ws/runs/" + id));
    std::vector<int> frames(size_t(clients), 0);
    std::vector<std::vector<double>> latency_ms{size_t(clients)};
    const long step0 = http(server.port(), "GET", "/api/runs/" + id).json()["live"]["step"];
    const auto start = Clock::now();
    std::vector<std::thread> readers;
    for (int i = 0; i < clients; ++i)
      readers.emplace_back([&, i] {
        while (Clock::now() - start < window) {
          auto message = sockets[size_t(i)]->read_json(std::chrono::milliseconds(2000));
          if (!message) break;
          if ((*message)["type"] != "frame") continue;
          ++frames[size_t(i)];
          latency_ms[size_t(i)].push_back(double(wall_now_us() - (*message)["wall_us"].get<std::int64_t>()) / 1000.0);
        }
      });
    for (auto& t : readers) t.join();
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    const long step1 = http(server.port(), "GET", "/api/runs/" + id).json()["live"]["step"];
    steps_per_s = double(step1 - step0) / seconds;
    std::vector<double> all;
    mean_fps = 0;
    for (int i = 0; i < clients; ++i) {
      const double fps = frames[size_t(i)] / seconds;
      min_fps = std::min(min_fps, fps);
      mean_fps += fps / clients;
      all.insert(all.end(), latency_ms[size_t(i)].begin(), latency_ms[size_t(i)].end());
    }
    std::sort(all.begin(), all.end());
    if (!all.empty()) {
      p50 = all[all.size() / 2];
      p99 = all[std::min(all.size() - 1, size_t(double(all.size()) * 0.99))];
      p90 = all[size_t(double(all.size()) * 0.90)];
      max_latency = all.back();
    }
    http_json(server.port(), "POST", "/api/runs/" + id + "/control", {{"action", "stop"}});
  }
  state.counters["clients"] = clients;
  state.counters["fps_min"] = min_fps;
  state.counters["fps_mean"] = mean_fps;
  state.counters["latency_p50_ms"] = p50;
  state.counters["latency_p90_ms"] = p90;
  state.counters["latency_p99_ms"] = p99;
  state.counters["latency_max_ms"] = max_latency;
  state.counters["sim_steps_per_s"] = steps_per_s;  // 100 at rate 1 with dt = 0.01
}
BENCHMARK(BM_WebSocketFanout50)->Arg(10)->Arg(50)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

// Each client steers its own live run (one controller per run) at about 50
// inputs/s, alternating a parameter change and an obstacle drag, and times
// each message to its ack (frames and snapshots in between are skipped).
void BM_LiveInputLatency(benchmark::State& state) {
  const int clients = int(state.range(0));
  const auto window = std::chrono::seconds(5);
  ServerProcess server;
  json scenario = json::parse(http(server.port(), "GET", "/api/scenarios/01_planar7_obstacles").body);
  scenario["duration"] = 600;
  double p50 = 0, p99 = 0, max_latency = 0;
  long acks = 0, errors = 0;
  for (auto _ : state) {
    std::vector<std::string> ids;
    for (int i = 0; i < clients; ++i)
      ids.push_back(std::to_string(
          http_json(server.port(), "POST", "/api/runs", {{"scenario", scenario}, {"rate", 10}}).json()["id"].get<long>()));
    std::vector<std::unique_ptr<WsClient>> sockets;
    for (int i = 0; i < clients; ++i)
      sockets.push_back(std::make_unique<WsClient>(server.port(), "/ws/runs/" + ids[size_t(i)] + "?client=steer" +
                                                                      std::to_string(i)));
    std::vector<std::vector<double>> latency_ms{size_t(clients)};
    std::atomic<long> ack_count{0}, error_count{0};
    const auto start = Clock::now();
    std::vector<std::thread> steerers;
    for (int i = 0; i < clients; ++i)
      steerers.emplace_back([&, i] {
        WsClient& ws = *sockets[size_t(i)];
        for (int k = 0; Clock::now() - start < window; ++k) {
          const json input = k % 2 == 0
                                 ? json{{"type", "input"}, {"kind", "params"}, {"payload", {{"gain", 4 + k % 4}}}}
                                 : json{{"type", "input"},
                                        {"kind", "obstacle"},
                                        {"payload", {{"id", "box"}, {"position", {1.1 + 0.001 * (k % 50), -0.05}}}}};
          const auto sent = Clock::now();
          ws.send(input.dump());
          for (;;) {
            auto message = ws.read_json(std::chrono::milliseconds(5000));
            if (!message) return;
            const std::string type = (*message)["type"];
            if (type != "ack" && type != "error") continue;
            (type == "ack" ? ack_count : error_count) += 1;
            latency_ms[size_t(i)].push_back(std::chrono::duration<double, std::milli>(Clock::now() - sent).count());
            break;
          }
          std::this_thread::sleep_until(sent + std::chrono::milliseconds(20));
        }
      });
    for (auto& t : steerers) t.join();
    std::vector<double> all;
    for (const auto& l : latency_ms) all.insert(all.end(), l.begin(), l.end());
    std::sort(all.begin(), all.end());
    if (!all.empty()) {
      p50 = all[all.size() / 2];
      p99 = all[std::min(all.size() - 1, size_t(double(all.size()) * 0.99))];
      max_latency = all.back();
    }
    acks = ack_count;
    errors = error_count;
    for (const std::string& id : ids) http_json(server.port(), "POST", "/api/runs/" + id + "/control", {{"action", "stop"}});
  }
  state.counters["clients"] = clients;
  state.counters["acks"] = double(acks);
  state.counters["errors"] = double(errors);
  state.counters["input_p50_ms"] = p50;
  state.counters["input_p99_ms"] = p99;
  state.counters["input_max_ms"] = max_latency;
}
BENCHMARK(BM_LiveInputLatency)->Arg(20)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

void BM_ConcurrentBatchRuns(benchmark::State& state) {
  const int runs = int(state.range(0));
  ServerProcess server;
  int completed = 0, stored = 0;
  for (auto _ : state) {
    std::atomic<int> ok{0};
    std::vector<std::thread> threads;
    for (int i = 0; i < runs; ++i)
      threads.emplace_back([&] {
        const HttpResult r = http_json(server.port(), "POST", "/api/runs",
                                       {{"scenario", "01_planar7_obstacles"}, {"mode", "batch"}, {"method", "dls"}});
        if (r.status == 200 && r.json()["status"] == "completed") ++ok;
      });
    for (auto& t : threads) t.join();
    completed = ok;
    stored = 0;
    for (const json& run : http(server.port(), "GET", "/api/runs?limit=1000&status=completed").json())
      if (run["frames"] == run["summary"]["steps"]) ++stored;
  }
  state.counters["runs"] = runs;
  state.counters["completed"] = completed;
  state.counters["stored_complete"] = stored;
}
BENCHMARK(BM_ConcurrentBatchRuns)->Arg(100)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace
}  // namespace rrlab::testing
