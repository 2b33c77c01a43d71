// `rrlab serve`: database, frame writer, run manager, listener and an I/O
// thread pool; SIGINT/SIGTERM stop runs (stored as "stopped"), flush frames
// and exit.
#include <boost/asio/signal_set.hpp>
#include <filesystem>
#include <iostream>
#include <thread>
#include <vector>

#include <rrlab/server/app/sweep_jobs.hpp>
#include <rrlab/server/net/sessions.hpp>
#include <rrlab/storage/disk_reserve.hpp>
#include <rrlab/storage/frame_writer.hpp>
#include <rrlab/storage/migrations.hpp>
#include <rrlab/storage/run_store.hpp>

#include "cli.hpp"

namespace rrlab::cli {

int serve(const ServeOptions& options) {
  using namespace rrlab::server;
  try {
    for (const auto& origin : options.allow_origins)
      if (normalize_origin(origin).empty())
        throw std::runtime_error("--allow-origin " + origin + ": expected scheme://host[:port], e.g. http://localhost:3000");
    if (!options.token.empty() && !token_problem(options.token).empty())
      throw std::runtime_error("--token / RRLAB_TOKEN: " + token_problem(options.token));
    if (options.token.empty() && !options.allow_anonymous && !is_loopback_host(options.host))
      throw std::runtime_error(
          "refusing to serve " + options.host +
          " without a token: every machine that reaches it could start, steer and delete runs. Set a token "
          "(RRLAB_TOKEN=... or --token TOKEN; clients send Authorization: Bearer TOKEN), or pass "
          "--allow-anonymous if the network is trusted, or bind --host 127.0.0.1");
    const std::filesystem::path db(options.db);
    if (db.has_parent_path()) std::filesystem::create_directories(db.parent_path());
    storage::RunStore store(options.db, storage::DiskReserve::kDefaultBytes);  // room for deletes on a full disk
    if (options.test_db_max_pages > 0) store.set_max_page_count(options.test_db_max_pages);
    if (options.test_db_read_only) store.set_query_only();
    storage::FrameWriter writer(store);
    ServerLimits limits;
    limits.default_display_hz = options.display_hz;
    static_cast<Quotas&>(limits) = options.quotas;
    RunManager runs(store, writer, find_dir(options.scenarios_dir, "scenarios"), limits);

    NetLimits net_limits;
    net_limits.body_limit = options.body_limit;
    net_limits.ws_stall_timeout = std::chrono::milliseconds(options.ws_stall_ms);
    net_limits.export_budget = options.export_memory;
    net_limits.test_build_delay = std::chrono::milliseconds(options.test_build_delay_ms);
    net_limits.peers = {options.connections_per_address, options.max_websockets, options.websockets_per_address,
                        options.websockets_per_client, options.websocket_fair_share,
                        options.websocket_newcomer_reserve};
    auto state = std::make_shared<ServerState>(runs, ServerInfo{RRLAB_VERSION, std::chrono::steady_clock::now()},
                                               find_dir(options.web_dir, "web"), net_limits);
    state->info.websockets = &state->websockets;
    state->info.building = &state->building;
    net::io_context ioc(options.threads);
    const unsigned short port = start_listener(ioc, options.host, options.port, state);
    // the listener accepts nothing before ioc.run(): the bound port is known in time
    state->access = AccessConfig{options.host,          port,         options.allow_hosts, options.allow_origins,
                                 options.token,         options.public_read};
    std::cout << "rrlab: serving http://" << options.host << ":" << port << "/ (database " << options.db;
    if (store.interrupted_at_open() > 0) std::cout << ", " << store.interrupted_at_open() << " runs marked interrupted";
    if (store.migrated_from() > 0 && store.migrated_from() < storage::current_schema_version())
      std::cout << ", migrated from schema version " << store.migrated_from();
    std::cout << ")";
    if (!options.token.empty()) std::cout << (options.public_read ? "; token required to change" : "; token required");
    std::cout << std::endl;

    net::signal_set signals(ioc, SIGINT, SIGTERM);
    signals.async_wait([&](beast::error_code, int) { ioc.stop(); });
    std::vector<std::thread> pool;
    for (int i = 1; i < options.threads; ++i) pool.emplace_back([&] { ioc.run(); });
    ioc.run();
    for (auto& t : pool) t.join();
    runs.sweeps().interrupt();  // a report being built on a worker is abandoned: the pool joins at once
    state->workers.stop();   // no scenario is built, nor a run started or deleted, once the manager stops
    state->exports.stop();   // no export worker may read the store once it goes
    runs.stop_all();
    writer.flush();
    std::cout << "rrlab: stopped" << std::endl;
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "rrlab: error: " << e.what() << '\n';
    return 2;
  }
}

}  // namespace rrlab::cli
