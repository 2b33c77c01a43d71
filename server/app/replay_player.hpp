// Plays a stored run's frames to WebSocket clients at a chosen speed, with
// pause and seek. Link geometry is recomputed from the stored q; obstacles
// follow the scenario and the run's recorded obstacle events.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <rrlab/server/app/frame_geometry.hpp>
#include <rrlab/server/app/frame_source.hpp>
#include <rrlab/server/app/recorded_scene.hpp>
#include <rrlab/server/app/run_types.hpp>
#include <rrlab/sim/simulator.hpp>
#include <rrlab/storage/run_store.hpp>

namespace rrlab::server {

class ReplayPlayer final : public FrameSource, public std::enable_shared_from_this<ReplayPlayer> {
 public:
  // Throws DomainError when the run cannot be replayed.
  ReplayPlayer(storage::RunStore& store, const storage::RunRecord& run, double speed, std::int64_t from,
               double display_hz);
  void start();
  void stop();
  void wait_exited();  // after stop(): returns once the playback thread has ended
  bool exited();
  void set_id(std::int64_t id) { id_ = id; }
  // Who started it (RunManager::add_replay), and since when.
  void set_owner(std::string owner) { owner_ = std::move(owner); }
  const std::string& owner() const { return owner_; }
  std::chrono::steady_clock::time_point created() const { return created_; }
  // A WebSocket client is connected, or none has been yet and it was made
  // less than `grace` ago (its client is still connecting).
  bool in_use(std::chrono::steady_clock::duration grace) {
    return subscribers_.size() > 0 ||
           (!subscribers_.ever_added() && std::chrono::steady_clock::now() - created_ < grace);
  }
  std::int64_t run_id() const { return run_.id; }  // the stored run it plays
  bool playing();

  // Plays, pauses, changes speed or seeks; the status. Throws DomainError
  // (invalid: a seek with no frame, a frame the run does not have).
  nlohmann::json control(const ReplayCommand& command);
  nlohmann::json status();

  std::string snapshot() override;
  PublishedFrame latest() override;
  Subscribers& subscribers() override { return subscribers_; }

 private:
  void loop();
  void show_locked(std::int64_t seq);  // the frame at seq becomes the published one
  nlohmann::json status_locked() const;

  storage::RunStore& store_;
  storage::RunRecord run_;
  std::unique_ptr<RecordedScene> scene_;     // model, scene and method at the shown frame
  std::unique_ptr<FrameGeometry> geometry_;  // links, nearest obstacles, ellipsoid of the shown q
  std::int64_t id_ = 0;
  std::string owner_;
  const std::chrono::steady_clock::time_point created_ = std::chrono::steady_clock::now();
  double display_hz_;

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool playing_ = true, stopping_ = false;
  double speed_, playhead_ = 0;
  std::int64_t shown_ = -1;
  Frame frame_;
  std::string encoded_;
  PublishedFrame published_;
  Subscribers subscribers_;
  bool exited_ = false;
  std::condition_variable exited_cv_;
};

}  // namespace rrlab::server
