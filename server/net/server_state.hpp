// What every connection shares: the run manager, limits, access rules and the web root.
#pragma once

#include <atomic>
#include <chrono>
#include <string>

#include <rrlab/server/app/export_pool.hpp>
#include <rrlab/server/app/run_manager.hpp>
#include <rrlab/server/app/worker_pool.hpp>
#include <rrlab/server/net/auth_throttle.hpp>
#include <rrlab/server/net/peer_limits.hpp>
#include <rrlab/server/net/request_guard.hpp>
#include <rrlab/server/routes/routes.hpp>

namespace rrlab::server {

struct NetLimits {
  std::size_t body_limit = 1 << 20;                   // bytes per request body (413 beyond)
  std::size_t header_limit = 16 << 10;                // request line + header fields (431 beyond)
  std::size_t url_limit = 8 << 10;                    // request target, query included (414 beyond)
  std::chrono::seconds read_timeout{30};              // per request
  std::size_t ws_message_limit = 64 << 10;            // bytes per incoming WebSocket message
  int ws_messages_per_second = 200;                   // incoming, per socket (errors beyond)
  std::chrono::milliseconds ws_stall_timeout{5000};   // a write pending this long drops the client
  PeerCaps peers;  // connections and WebSockets per peer (net/peer_limits.hpp)
  // Streamed exports (GET /api/runs/{id}/frames): chunks of about this many
  // bytes; each export reserves twice that (its chunk, and the frame it may
  // run over by) from a budget shared by all (503 with Retry-After beyond).
  // 64 MiB / 128 KiB: 512 exports at once.
  std::size_t export_chunk = 64 << 10;
  std::size_t export_budget = 64 << 20;  // serve --export-memory
  int export_threads = 2;
  // Slow work (building scenarios, deleting runs): off the I/O threads, at
  // most this many requests waiting (503 busy beyond).
  int worker_threads = 2;
  std::size_t worker_queue = 64;
  std::chrono::milliseconds test_build_delay{0};  // tests only: each slow request waits this long first
};

struct ServerState {
  ServerState(RunManager& runs, ServerInfo info, std::string web_root, NetLimits limits = {})
      : runs(runs), info(std::move(info)), web_root(std::move(web_root)), limits(limits) {}
  RunManager& runs;
  ServerInfo info;
  std::string web_root;
  NetLimits limits;
  AccessConfig access;  // Host/Origin/Content-Type rules (net/request_guard.hpp)
  AuthThrottle auth_failures;  // wrong tokens per address (429 beyond)
  std::atomic<int> websockets{0};
  std::atomic<int> building{0};  // requests on the worker pool (/api/health "building")
  PeerLimits peers{limits.peers};
  ExportPool exports{limits.export_threads, limits.export_budget};
  WorkerPool workers{limits.worker_threads, 0, limits.worker_queue};
};

}  // namespace rrlab::server
