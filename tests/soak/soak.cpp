// A bounded soak of `rrlab serve` on loopback: for --seconds (default 150)
// several clients at once drive live runs over the WebSocket (obstacle
// drags, joystick, parameter changes; each acknowledged), steer a live
// compare group over REST, start batch runs, play and re-simulate replays,
// download large exports, and keep 20 exports of a 64-joint run open without
// ever reading them. Reports the server's resident memory at start, after
// the warm-up (--warmup, default 45 s) and at the end, and the WebSocket
// round trip (input sent -> its ack) at p50/p99/max. Then stops the server
// (SIGTERM: exit status 0) and runs `rrlab replay --verify` on every stored
// run. Fails on a crash, an unexpected answer, memory growth after the
// warm-up over --rss-growth-mib (default 16), or a run that does not verify.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "chain_scenario.hpp"
#include "client.hpp"
#include "raw_connection.hpp"
#include "server_process.hpp"

using namespace rrlab::testing;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

namespace {

struct Options {
  double seconds = 150, warmup = 45, rss_growth_mib = 16;
};

// Problems seen by any client: each is printed once it happens, and counted.
std::atomic<int> g_problems{0};
std::mutex g_print;
void problem(const std::string& what) {
  ++g_problems;
  std::lock_guard lock(g_print);
  std::cerr << "soak: PROBLEM: " << what << '\n';
}
void expect_status(const HttpResult& r, int status, const std::string& what) {
  if (r.status != status) problem(what + ": " + std::to_string(r.status) + " " + r.body.substr(0, 300));
}

std::atomic<bool> g_stop{false};
// The soak is about time itself: its clients pace themselves as people and
// scripts do (a message every 20 ms, a new run every few seconds) for the
// soak's duration. Not a wait for state: those poll with a deadline.
void sleep_ms(int ms) {
  const auto until = Clock::now() + std::chrono::milliseconds(ms);
  while (!g_stop && Clock::now() < until) std::this_thread::sleep_for(std::chrono::milliseconds(std::min(ms, 50)));
}

// WebSocket round trips, in milliseconds.
std::mutex g_latency_mutex;
std::vector<double> g_latency_ms;

// The next reply (ack or error) to a message sent on `ws`, skipping frames.
std::optional<json> reply(WsClient& ws) {
  const auto deadline = Clock::now() + std::chrono::seconds(10);
  while (Clock::now() < deadline) {
    auto message = ws.read_json(std::chrono::milliseconds(500));
    if (!message) continue;
    const std::string type = message->value("type", "");
    if (type == "ack" || type == "error") return message;
  }
  return std::nullopt;
}

// One live run at a time, steered over its WebSocket at ~50 messages/s for
// ~20 s, then stopped; again until the end.
void live_client(unsigned short port, int index) {
  const char* methods[] = {"closest_point", "gpm", "dls"};
  int cycle = 0;
  while (!g_stop) {
    const HttpResult started = http_json(
        port, "POST", "/api/runs",
        {{"scenario", "04_planar7_joystick"}, {"method", methods[(index + cycle++) % 3]}, {"rate", 1}});
    expect_status(started, 201, "live run start");
    if (started.status != 201) return sleep_ms(1000);
    const std::string id = std::to_string(started.json().at("id").get<long>());
    try {
      WsClient ws(port, "/ws/runs/" + id);
      if (!ws.read_type("snapshot")) problem("live run " + id + ": no snapshot");
      const auto cycle_end = Clock::now() + std::chrono::seconds(20);
      for (int k = 0; !g_stop && Clock::now() < cycle_end; ++k) {
        const double s = std::sin(k / 10.0), c = std::cos(k / 13.0);
        json message;
        switch (k % 3) {
          case 0:  // a drag: the disc follows the pointer
            message = {{"type", "input"},
                       {"kind", "obstacle"},
                       {"payload", {{"id", "disc"}, {"position", {0.3 + 0.1 * s, 1.2 + 0.05 * c}}}}};
            break;
          case 1:  // the joystick
            message = {{"type", "input"}, {"kind", "joystick"}, {"payload", {{"linear", {0.05 * s, 0.05 * c}}}}};
            break;
          default:  // a parameter change (every method here takes a damping or gain)
            message = {{"type", "input"}, {"kind", "params"}, {"payload", json::object()}};
            if (std::string(methods[(index + cycle - 1) % 3]) == "dls")
              message["payload"]["lambda"] = 0.02 + 0.01 * (k % 4);
            else
              message["payload"]["gain"] = 3.0 + (k % 4);
        }
        const auto t0 = Clock::now();
        ws.send(message.dump());
        const auto answer = reply(ws);
        const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
        if (!answer) {
          problem("live run " + id + ": no reply to " + message.dump());
        } else if ((*answer)["type"] != "ack") {
          problem("live run " + id + ": " + answer->dump());
        } else {
          std::lock_guard lock(g_latency_mutex);
          g_latency_ms.push_back(ms);
        }
        sleep_ms(20);
      }
    } catch (const std::exception& e) {
      problem("live run " + id + ": " + e.what());
    }
    expect_status(http_json(port, "POST", "/api/runs/" + id + "/control", {{"action", "stop"}}), 200,
                  "live run stop");
  }
}

// A live compare group of three methods, steered over REST, ~20 s each.
void compare_client(unsigned short port) {
  while (!g_stop) {
    const HttpResult started =
        http_json(port, "POST", "/api/compare",
                  {{"scenario", "04_planar7_joystick"}, {"methods", {"pinv", "dls", "closest_point"}},
                   {"mode", "live"}, {"rate", 1}});
    expect_status(started, 201, "compare start");
    if (started.status != 201) return sleep_ms(1000);
    const json runs = started.json().at("runs");
    const std::string first = std::to_string(runs[0]["id"].get<long>());
    const std::string last = std::to_string(runs[2]["id"].get<long>());
    const auto cycle_end = Clock::now() + std::chrono::seconds(20);
    for (int k = 0; !g_stop && Clock::now() < cycle_end; ++k) {
      const double s = std::sin(k / 5.0);
      expect_status(http_json(port, "POST", "/api/runs/" + first + "/joystick", {{"linear", {0.05 * s, -0.03 * s}}}),
                    200, "compare joystick");
      if (k % 4 == 0)
        expect_status(http_json(port, "PATCH", "/api/runs/" + last + "/params", {{"gain", 3.0 + k % 3}}), 200,
                      "compare params");
      if (k % 5 == 0)
        expect_status(http_json(port, "PUT", "/api/runs/" + first + "/obstacles/box", {{"position", {1.1 + 0.05 * s, -0.05}}}),
                      200, "compare drag");
      sleep_ms(100);
    }
    expect_status(http_json(port, "POST", "/api/runs/" + first + "/control", {{"action", "stop"}}), 200,
                  "compare stop");
  }
}

std::atomic<long> g_last_batch{0};

// Batch runs of several scenarios and methods, one every ~0.5 s.
void batch_client(unsigned short port) {
  const char* scenarios[] = {"01_planar7_obstacles", "02_spatial_xz_reach", "03_dh7_pose"};
  const char* methods[] = {"pinv", "dls", "gpm"};
  for (int k = 0; !g_stop; ++k) {
    const HttpResult r = http_json(port, "POST", "/api/runs",
                                   {{"scenario", scenarios[k % 3]}, {"method", methods[(k / 3) % 3]},
                                    {"mode", "batch"}, {"steps", 300}});
    expect_status(r, 200, "batch run");
    if (r.status == 200) g_last_batch = r.json().at("id").get<long>();
    sleep_ms(500);
  }
}

// Frame replays of the latest batch run (play, pause, seek, play), and every
// third time a re-simulation that must be identical.
void replay_client(unsigned short port) {
  for (int k = 0; !g_stop; ++k) {
    const long run = g_last_batch;
    if (run == 0) {
      sleep_ms(200);
      continue;
    }
    const std::string base = "/api/runs/" + std::to_string(run);
    if (k % 3 == 2) {
      const HttpResult r = http_json(port, "POST", base + "/replay", {{"mode", "resimulate"}});
      expect_status(r, 200, "resimulate");
      if (r.status == 200 && r.json().value("identical", false) != true) problem("resimulation differs: " + r.body);
      continue;
    }
    const HttpResult r = http_json(port, "POST", base + "/replay", {{"mode", "frames"}, {"speed", 0.5}});  // 300 frames: 6 s or more, time to connect and read under load
    expect_status(r, 201, "frame replay");
    if (r.status != 201) {
      sleep_ms(500);
      continue;
    }
    try {
      const std::string rid = std::to_string(r.json().at("replay").get<long>());
      WsClient ws(port, r.json().at("ws").get<std::string>());
      for (int i = 0; i < 10; ++i)
        if (!ws.read_type("frame")) problem("replay " + rid + ": no frame");
      const std::string control = "/api/replays/" + rid + "/control";
      expect_status(http_json(port, "POST", control, {{"action", "pause"}}), 200, "replay pause");
      expect_status(http_json(port, "POST", control, {{"action", "seek"}, {"seq", 100}}), 200, "replay seek");
      expect_status(http_json(port, "POST", control, {{"action", "play"}}), 200, "replay play");
      for (int i = 0; i < 5; ++i)
        if (!ws.read_type("frame")) problem("replay " + rid + ": no frame after play");
    } catch (const std::exception& e) {
      problem(std::string("replay: ") + e.what());
    }
    sleep_ms(500);
  }
}

json long_chain(int dof, int steps) { return chain_scenario("soak_chain" + std::to_string(dof), dof, steps); }

// 20 exports of the large run that are never read past their header; the
// server drops a connection whose write makes no progress for 30 s, so a
// new set is opened every 25 s.
void stalled_exports(unsigned short port, const std::string& target) {
  while (!g_stop) {
    std::vector<std::unique_ptr<RawConnection>> stalled;
    for (int i = 0; i < 20 && !g_stop; ++i) {
      try {
        stalled.push_back(std::make_unique<RawConnection>(port));
        stalled.back()->write("GET " + target + " HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port) + "\r\n\r\n");
        const std::string head = stalled.back()->read_until("\r\n\r\n", std::chrono::seconds(30));
        if (status_of(head) != 200) problem("stalled export: " + head.substr(0, 200));
      } catch (const std::exception& e) {
        problem(std::string("stalled export: ") + e.what());
      }
    }
    sleep_ms(25'000);
  }
}

// The large export read whole, again and again: the same bytes each time.
void export_reader(unsigned short port, const std::string& target, std::size_t expected_size) {
  while (!g_stop) {
    const HttpResult r = http(port, "GET", target);
    expect_status(r, 200, "export");
    if (r.status == 200 && r.body.size() != expected_size)
      problem("export of " + std::to_string(r.body.size()) + " bytes, not " + std::to_string(expected_size));
    const HttpResult csv = http(port, "GET", target + "?format=csv&stride=10");
    expect_status(csv, 200, "csv export");
    if (std::count(csv.body.begin(), csv.body.end(), '\n') != 2001) problem("csv export: not 2001 lines");
    sleep_ms(1000);
  }
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, std::size_t(p * double(v.size())))];
}

double mib(long kib) { return double(kib) / 1024.0; }

}  // namespace

int main(int argc, char** argv) {
  Options options;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string name = argv[i];
    const double value = std::atof(argv[i + 1]);
    if (name == "--seconds") options.seconds = value;
    else if (name == "--warmup") options.warmup = value;
    else if (name == "--rss-growth-mib") options.rss_growth_mib = value;
    else return std::cerr << "usage: rrlab_soak [--seconds S] [--warmup S] [--rss-growth-mib M]\n", 2;
  }
  ServerProcess server;
  const unsigned short port = server.port();
  const long rss_start = resident_kib(server.pid());
  std::cout << "soak: rrlab serve pid " << server.pid() << " on port " << port << ", " << options.seconds
            << " s (warm-up " << options.warmup << " s)" << std::endl;

  // the large run: 64 joints, 20,000 frames (a 65 MB JSON export)
  const HttpResult big =
      http_json(port, "POST", "/api/runs", {{"scenario", long_chain(64, 20'000)}, {"mode", "batch"}});
  if (big.status != 200) return std::cerr << "soak: the large run failed: " << big.body << '\n', 1;
  const std::string export_target = "/api/runs/" + std::to_string(big.json().at("id").get<long>()) + "/frames";
  const HttpResult first_export = http(port, "GET", export_target);
  if (first_export.status != 200) return std::cerr << "soak: the first export failed\n", 1;

  const auto started = Clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - started).count(); };
  std::vector<std::thread> clients;
  for (int i = 0; i < 3; ++i) clients.emplace_back(live_client, port, i);
  clients.emplace_back(compare_client, port);
  clients.emplace_back(batch_client, port);
  clients.emplace_back(replay_client, port);
  clients.emplace_back(stalled_exports, port, export_target);
  clients.emplace_back(export_reader, port, export_target, first_export.body.size());

  // resident memory once a second; "after warm-up" and "end" are the highest
  // of the last 5 s before each point, so a passing dip does not hide growth
  std::vector<std::pair<double, long>> samples;
  long health_failures = 0;
  double health_worst_ms = 0;
  while (elapsed() < options.seconds) {
    std::this_thread::sleep_for(std::chrono::seconds(1));  // the sampling period (about time itself)
    const long rss = resident_kib(server.pid());
    if (rss < 0) {
      problem("the server is gone");
      break;
    }
    samples.emplace_back(elapsed(), rss);
    const auto t0 = Clock::now();
    const HttpResult health = http(port, "GET", "/api/health");
    health_worst_ms = std::max(health_worst_ms, std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    if (health.status != 200) ++health_failures;
  }
  const auto highest = [&](double from, double to) {
    long best = -1;
    for (const auto& [t, rss] : samples)
      if (t >= from && t <= to) best = std::max(best, rss);
    return best;
  };
  const long rss_warm = highest(options.warmup - 5, options.warmup);
  const long rss_end = highest(options.seconds - 5, options.seconds);
  const long rss_peak = highest(options.warmup, options.seconds);
  g_stop = true;
  for (auto& t : clients) t.join();

  std::vector<long> ids;
  for (int offset = 0;; offset += 1000) {
    const HttpResult list = http(port, "GET", "/api/runs?limit=1000&offset=" + std::to_string(offset));
    if (list.status != 200) break;
    const json runs = list.json().is_array() ? list.json() : list.json().value("runs", json::array());
    for (const json& run : runs) ids.push_back(run.at("id").get<long>());
    if (runs.size() < 1000) break;
  }
  const bool survived = server.running() && resident_kib(server.pid()) > 0;
  const int exit_status = server.stop();
  int verified = 0;
  std::vector<long> failed;
  for (long id : ids) {
    const CommandResult r = run_rrlab({"replay", std::to_string(id), "--db", server.db(), "--verify"});
    if (r.exit_code == 0)
      ++verified;
    else
      failed.push_back(id);
  }

  std::vector<double> latency;
  {
    std::lock_guard lock(g_latency_mutex);
    latency = g_latency_ms;
  }
  std::cout.setf(std::ios::fixed);
  std::cout.precision(1);
  std::cout << "soak: RSS start " << mib(rss_start) << " MiB, after warm-up " << mib(rss_warm) << " MiB, end "
            << mib(rss_end) << " MiB (peak after warm-up " << mib(rss_peak) << " MiB; growth after warm-up "
            << mib(rss_end - rss_warm) << " MiB, bound " << options.rss_growth_mib << ")\n";
  std::cout.precision(2);
  std::cout << "soak: WebSocket input->ack over " << latency.size() << " messages: p50 " << percentile(latency, 0.5)
            << " ms, p99 " << percentile(latency, 0.99) << " ms, max " << percentile(latency, 1.0) << " ms\n";
  std::cout << "soak: /api/health once a second: " << health_failures << " failures, slowest " << health_worst_ms
            << " ms\n";
  std::cout << "soak: " << ids.size() << " stored runs, " << verified << " verified by rrlab replay --verify";
  for (long id : failed) std::cout << (id == failed.front() ? "; failed: " : ", ") << id;
  std::cout << "\nsoak: server " << (survived ? "alive" : "GONE") << " at the end, exit status " << exit_status
            << "; " << g_problems.load() << " problems" << std::endl;

  bool ok = survived && exit_status == 0 && g_problems == 0 && failed.empty() && !ids.empty() &&
            health_failures == 0 && !latency.empty();
  if (rss_warm < 0 || rss_end < 0 || mib(rss_end - rss_warm) > options.rss_growth_mib ||
      mib(rss_peak - rss_warm) > 2 * options.rss_growth_mib) {
    std::cout << "soak: memory grew after the warm-up\n";
    ok = false;
  }
  std::cout << (ok ? "soak: PASS" : "soak: FAIL") << std::endl;
  return ok ? 0 : 1;
}
