#include <rrlab/server/app/replay_player.hpp>

#include <chrono>
#include <cmath>
#include <thread>

#include <rrlab/server/api/errors.hpp>
#include <rrlab/server/app/stream_json.hpp>
#include <rrlab/sim/run_inputs.hpp>
#include <rrlab/storage/frame_codec.hpp>
#include <rrlab/storage/resimulation.hpp>
#include <rrlab/util/nesting_depth.hpp>

namespace rrlab::server {

using nlohmann::json;

ReplayPlayer::ReplayPlayer(storage::RunStore& store, const storage::RunRecord& run, double speed,
                           std::int64_t from, double display_hz)
    : store_(store), run_(run), display_hz_(display_hz), speed_(speed), playhead_(double(from)) {
  if (run_.frames < 1)
    throw DomainError(Problem::conflict, "wrong_state", "run " + std::to_string(run_.id) + " has no stored frames");
  if (from < 0 || from >= run_.frames)
    throw DomainError(Problem::invalid, "invalid", "must be in [0, " + std::to_string(run_.frames - 1) + "]", "from");
  try {
    scene_ = std::make_unique<RecordedScene>(run_, store_.events(run_.id));
    const Simulator& sim = scene_->sim();
    geometry_ = std::make_unique<FrameGeometry>(sim.model(), sim.scene(), sim.scenario().task.space);
  } catch (const std::exception& e) {
    throw DomainError(Problem::conflict, "wrong_state", std::string("the stored scenario no longer loads: ") + e.what());
  }
  std::lock_guard lock(mutex_);
  show_locked(from);
}

void ReplayPlayer::start() {
  try {
    std::thread([self = shared_from_this()] { self->loop(); }).detach();
  } catch (...) {
    std::lock_guard lock(mutex_);
    exited_ = true;  // nothing to wait for
    throw;
  }
}

void ReplayPlayer::stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
}

bool ReplayPlayer::exited() {
  std::lock_guard lock(mutex_);
  return exited_;
}

bool ReplayPlayer::playing() {
  std::lock_guard lock(mutex_);
  return playing_ && !stopping_;
}

void ReplayPlayer::wait_exited() {
  std::unique_lock lock(mutex_);
  exited_cv_.wait(lock, [&] { return exited_; });
}

void ReplayPlayer::show_locked(std::int64_t seq) {
  if (seq == shown_) return;
  scene_->seek(seq);  // the obstacle and method inputs recorded up to this frame
  bool found = false;
  store_.frames(run_.id, seq, seq, 1, [&](const storage::StoredFrame& f) {
    frame_ = storage::unpack_frame(f.data);
    found = true;
    return false;
  });
  if (!found) return;
  shown_ = seq;
  Simulator& sim = scene_->sim();
  sim.scene().advance_to(frame_.t);
  const FrameContext context{run_.id, seq, scene_->version(), playing_ ? "playing" : "paused"};
  encode_frame(context, frame_, sim.model(), sim.scene(), *geometry_, encoded_);
  published_.version += 1;
  published_.scene_version = scene_->version();
  published_.text = std::make_shared<const std::string>(encoded_);
  subscribers_.notify_all();
}

void ReplayPlayer::loop() {
  const auto period = std::chrono::duration<double>(1.0 / display_hz_);
  const double dt = scene_->sim().scenario().dt;
  std::unique_lock lock(mutex_);
  while (!stopping_) {
    wake_.wait_for(lock, period, [&] { return stopping_; });
    if (stopping_ || !playing_) continue;
    playhead_ += speed_ * period.count() / dt;
    if (playhead_ >= double(run_.frames - 1)) {
      playhead_ = double(run_.frames - 1);
      playing_ = false;  // stop at the end
    }
    try {
      show_locked(std::int64_t(playhead_));
    } catch (const std::exception&) {
      playing_ = false;  // a frame that cannot be read ends playback, not the server
    }
  }
  exited_ = true;
  exited_cv_.notify_all();
}

json ReplayPlayer::status_locked() const {
  return {{"replay", id_},       {"run", run_.id},       {"playing", playing_}, {"speed", speed_},
          {"seq", shown_},       {"frames", run_.frames}, {"ws", "/ws/replays/" + std::to_string(id_)}};
}

json ReplayPlayer::status() {
  std::lock_guard lock(mutex_);
  return status_locked();
}

json ReplayPlayer::control(const ReplayCommand& command) {
  if (command.speed && !(*command.speed > 0 && *command.speed <= 1000))
    throw DomainError(Problem::invalid, "invalid", "must be in (0, 1000]", "speed");
  if (command.action == ReplayAction::seek && !command.seq)
    throw DomainError(Problem::invalid, "invalid", "seek needs a seq", "seq");
  if (command.seq && !(*command.seq >= 0 && *command.seq < double(run_.frames)))
    throw DomainError(Problem::invalid, "invalid", "must be in [0, " + std::to_string(run_.frames - 1) + "]", "seq");
  std::lock_guard lock(mutex_);
  if (command.speed) speed_ = *command.speed;
  if (command.action == ReplayAction::play) playing_ = true;
  if (command.action == ReplayAction::pause) playing_ = false;
  if (command.seq) {
    playhead_ = std::floor(*command.seq);
    show_locked(std::int64_t(playhead_));
  }
  return status_locked();
}

std::string ReplayPlayer::snapshot() {
  std::lock_guard lock(mutex_);
  const FrameContext context{run_.id, shown_, scene_->version(), playing_ ? "playing" : "paused"};
  json snap = snapshot_json(context, scene_->sim(), encoded_);
  snap["replay"] = id_;
  snap["frames"] = run_.frames;
  return snap.dump();
}

PublishedFrame ReplayPlayer::latest() {
  std::lock_guard lock(mutex_);
  return published_;
}

}  // namespace rrlab::server
