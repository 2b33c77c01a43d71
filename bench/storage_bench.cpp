// Storage throughput: 7-DOF frames packed and inserted in batched
// transactions, directly and through the FrameWriter's queue.
#include <benchmark/benchmark.h>
#include <stdlib.h>

#include <filesystem>

#include <rrlab/sim/frame_csv.hpp>
#include <rrlab/storage/frame_codec.hpp>
#include <rrlab/storage/frame_writer.hpp>
#include <rrlab/storage/run_store.hpp>

namespace rrlab::storage {
namespace {

Frame seven_dof_frame(long step) {
  Frame f;
  f.step = step;
  f.t = 0.01 * double(step);
  f.q = Eigen::VectorXd::Constant(7, 0.1 * double(step % 17));
  f.qdot = Eigen::VectorXd::Constant(7, 0.01);
  f.diagnostics = Eigen::VectorXd::Constant(2, 0.5);
  f.min_distance = 0.3;
  return f;
}

struct TempDb {
  TempDb() {
    std::string pattern = "/tmp/rrlab-bench-XXXXXX";
    dir = mkdtemp(pattern.data());
    path = dir + "/bench.db";
  }
  ~TempDb() { std::filesystem::remove_all(dir); }
  std::string dir, path;
};

NewRun bench_run() {
  NewRun r;
  r.scenario_name = "bench";
  r.scenario_json = "{}";
  r.method = "pinv";
  r.params_json = "{}";
  r.mode = "batch";
  r.dof = 7;
  return r;
}

// Frames per second inserted in batches of state.range(0) (one transaction each).
void BM_FrameInsertBatched(benchmark::State& state) {
  TempDb db;
  RunStore store(db.path);
  const auto run = store.create_run(bench_run());
  const auto batch_size = size_t(state.range(0));
  std::vector<std::pair<std::int64_t, StoredFrame>> batch(batch_size);
  std::int64_t seq = 0;
  for (auto _ : state) {
    for (auto& [id, f] : batch) {
      const Frame frame = seven_dof_frame(seq);
      id = run;
      f.seq = f.step = seq++;
      f.t = frame.t;
      f.min_distance = frame.min_distance;
      pack_frame(frame, f.data);
    }
    store.add_frames(batch);
  }
  state.counters["frames_per_s"] = benchmark::Counter(double(seq), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_FrameInsertBatched)->Arg(256)->Arg(1024)->Unit(benchmark::kMillisecond);

// The simulation thread's view: push() into the writer's queue, flushed at the end.
void BM_FrameWriterThroughput(benchmark::State& state) {
  TempDb db;
  RunStore store(db.path);
  const auto run = store.create_run(bench_run());
  std::int64_t seq = 0;
  {
    FrameWriter writer(store);
    for (auto _ : state) {
      for (int i = 0; i < 10000; ++i) {
        const Frame frame = seven_dof_frame(seq);
        StoredFrame f{seq, seq, frame.t, 0, frame.min_distance, false, {}};
        pack_frame(frame, f.data);
        ++seq;
        writer.push(run, std::move(f));
      }
      writer.flush();
    }
  }
  state.counters["frames_per_s"] = benchmark::Counter(double(seq), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_FrameWriterThroughput)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_PackFrame7Dof(benchmark::State& state) {
  const Frame frame = seven_dof_frame(3);
  std::string out;
  for (auto _ : state) {
    pack_frame(frame, out);
    benchmark::DoNotOptimize(out.data());
  }
}
BENCHMARK(BM_PackFrame7Dof);

void BM_UnpackFrame7Dof(benchmark::State& state) {
  const std::string blob = pack_frame(seven_dof_frame(3));
  for (auto _ : state) {
    Frame frame = unpack_frame(blob);
    benchmark::DoNotOptimize(frame.q.data());
  }
}
BENCHMARK(BM_UnpackFrame7Dof);

// One stored frame as GET /api/runs/{id}/frames writes it: blob decoded, then JSON text.
void BM_StoredFrameJson7Dof(benchmark::State& state) {
  const std::string blob = pack_frame(seven_dof_frame(3));
  std::string out;
  for (auto _ : state) {
    out.clear();
    append_stored_frame_json(3, unpack_frame(blob), out);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["bytes"] = double(out.size());
}
BENCHMARK(BM_StoredFrameJson7Dof);

// The same frame as a CSV row (the export's and `rrlab run --out`'s).
void BM_StoredFrameCsv7Dof(benchmark::State& state) {
  const std::string blob = pack_frame(seven_dof_frame(3));
  std::string out;
  for (auto _ : state) {
    out.clear();
    append_frame_csv(unpack_frame(blob), FrameOrigin::stored, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["bytes"] = double(out.size());
}
BENCHMARK(BM_StoredFrameCsv7Dof);

}  // namespace
}  // namespace rrlab::storage
