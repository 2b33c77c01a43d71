// A stored run's scene as a replay draws it at any frame: the run's scenario
// with its recorded inputs applied up to that frame, all but parameter
// changes and the joystick (they do not change the picture). Seeking back
// starts again from the scenario. The replay player, the drawn frames a page
// scrubs from its own memory and the one-file export all draw through it.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <rrlab/sim/simulator.hpp>
#include <rrlab/storage/run_store.hpp>

namespace rrlab::server {

class RecordedScene {
 public:
  // Throws what loading the stored scenario throws (std::exception).
  RecordedScene(const storage::RunRecord& run, std::vector<storage::StoredEvent> events);

  // The scene as it stood at frame `seq` (obstacles not yet advanced to its
  // time: the caller knows the frame's t). True when it changed since the
  // last call: an input applied, or started again for a seek back.
  bool seek(std::int64_t seq);

  Simulator& sim() { return *sim_; }
  const Simulator& sim() const { return *sim_; }
  // Counts every change: a client that drew an older version redraws the scene.
  std::uint64_t version() const { return version_; }
  // The recorded inputs that change the picture.
  std::size_t inputs() const { return events_.size(); }

 private:
  Scenario scenario_;
  std::vector<storage::StoredEvent> events_;  // those that change the picture
  std::unique_ptr<Simulator> sim_;             // never stepped: model, scene, method
  std::size_t next_event_ = 0;
  std::int64_t at_ = -1;
  std::uint64_t version_ = 1;
};

}  // namespace rrlab::server
