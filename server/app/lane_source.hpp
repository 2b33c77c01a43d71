// A live run's lane as a WebSocket frame source: its snapshot, what changed
// since a client's scene version, and the latest published frame. Messages
// from its clients are parsed by the routes (routes/socket_message.hpp) and
// reach the group as typed commands (RunGroup::control, RunGroup::input).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include <rrlab/server/app/frame_source.hpp>
#include <rrlab/server/app/run_group.hpp>
#include <rrlab/server/app/stream_json.hpp>

namespace rrlab::server {

class LaneSource final : public FrameSource {
 public:
  LaneSource(std::shared_ptr<RunGroup> group, int lane) : group_(std::move(group)), lane_(lane) {}

  std::string snapshot() override;
  SceneUpdate update_since(std::uint64_t since) override;
  PublishedFrame latest() override;
  Subscribers& subscribers() override;
  Controller* controller() override { return &group_->controller(); }

  RunGroup& group() { return *group_; }
  int lane() const { return lane_; }

 private:
  FrameContext context_of(const RunGroup::Lane& lane) const;
  std::string snapshot_locked();  // the group's lock held

  std::shared_ptr<RunGroup> group_;
  int lane_;
};

}  // namespace rrlab::server
