#include <rrlab/server/app/drawn_frames.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include <rrlab/server/api/errors.hpp>
#include <rrlab/server/app/frame_batches.hpp>
#include <rrlab/server/app/frame_geometry.hpp>
#include <rrlab/server/app/recorded_scene.hpp>
#include <rrlab/server/app/stream_json.hpp>
#include <rrlab/storage/frame_codec.hpp>

namespace rrlab::server {

namespace {

// Stored frames read per query (each drawn after the query: no read lock is
// held while links and distances are computed).
constexpr std::size_t kDrawnBatchRows = 128;

class DrawnFrames : public BodyStream {
 public:
  DrawnFrames(storage::RunStore& store, const storage::RunRecord& run, std::int64_t from, std::int64_t to,
              std::int64_t stride, std::unique_ptr<RecordedScene> scene)
      : run_(run.id), batches_(store, run.id, from, to, stride), scene_(std::move(scene)) {
    const Simulator& sim = scene_->sim();
    geometry_ = std::make_unique<FrameGeometry>(sim.model(), sim.scene(), sim.scenario().task.space);
    head_ = nlohmann::json{{"type", "drawn"}, {"run", run.id},         {"from", from},
                           {"to", to},        {"stride", stride},       {"frames", run.frames}}
                .dump() +
            '\n';
  }

  bool next(std::string& out, std::size_t target) override {
    out.clear();
    if (!head_.empty()) out.swap(head_);
    while (out.size() < target && !batches_.done())
      for (const storage::StoredFrame& f : batches_.next(kDrawnBatchRows)) append(f, out);
    if (!batches_.done()) return true;
    batches_.check_complete();
    return false;
  }

 private:
  void append(const storage::StoredFrame& stored, std::string& out) {
    frame_ = storage::unpack_frame(stored.data);
    Simulator& sim = scene_->sim();
    const bool changed = scene_->seek(stored.seq) || versions_ == 0;
    if (changed) ++versions_;
    sim.scene().advance_to(frame_.t);
    const FrameContext context{run_, stored.seq, versions_, "paused"};
    if (changed) {
      // the scene message a live stream sends, with the frame it starts at and the method then running
      nlohmann::json scene = scene_message_json(context, sim);
      scene["seq"] = stored.seq;
      scene["method"] = sim.method_name();
      out += scene.dump();
      out += '\n';
    }
    encode_frame(context, frame_, sim.model(), sim.scene(), *geometry_, encoded_);
    out += encoded_;
    out += '\n';
  }

  const std::int64_t run_;
  FrameBatches batches_;
  std::unique_ptr<RecordedScene> scene_;
  std::unique_ptr<FrameGeometry> geometry_;
  std::uint64_t versions_ = 0;  // scenes written
  std::string head_, encoded_;
  Frame frame_;
};

}  // namespace

std::shared_ptr<BodyStream> make_drawn_frames(storage::RunStore& store, const storage::RunRecord& run,
                                              std::int64_t from, std::int64_t to, std::int64_t stride) {
  if (run.frames < 1)
    throw DomainError(Problem::conflict, "wrong_state", "run " + std::to_string(run.id) + " has no stored frames",
                      "id");
  if (from < 0 || from > run.frames - 1)
    throw DomainError(Problem::invalid, "invalid", "must be in [0, " + std::to_string(run.frames - 1) + "]", "from");
  to = std::min({to, run.frames - 1, from + (kDrawnFramesPerRequest - 1) * stride});
  std::unique_ptr<RecordedScene> scene;
  try {
    scene = std::make_unique<RecordedScene>(run, store.events(run.id));
  } catch (const std::exception& e) {
    throw DomainError(Problem::conflict, "wrong_state",
                      "run " + std::to_string(run.id) + ": the stored scenario no longer loads: " + e.what(), "id");
  }
  return std::make_shared<DrawnFrames>(store, run, from, to, stride, std::move(scene));
}

}  // namespace rrlab::server
