#include <rrlab/server/app/lane_source.hpp>

namespace rrlab::server {

std::string LaneSource::snapshot() {
  auto lock = group_->lock_for_input();
  return snapshot_locked();
}

SceneUpdate LaneSource::update_since(std::uint64_t since) {
  auto lock = group_->lock_for_input();
  RunGroup::Lane& lane = group_->lanes_[size_t(lane_)];
  SceneUpdate update{{}, lane.scene_version};
  if (since < lane.snapshot_version) {
    update.messages.push_back(snapshot_locked());
    return update;
  }
  const FrameContext context = context_of(lane);
  if (since < lane.obstacles_version) update.messages.push_back(scene_message_json(context, *lane.sim).dump());
  if (since < lane.params_version) update.messages.push_back(params_message_json(context, *lane.sim).dump());
  return update;
}

PublishedFrame LaneSource::latest() {
  std::lock_guard lock(group_->publish_mutex_);
  return group_->lanes_[size_t(lane_)].published;
}

Subscribers& LaneSource::subscribers() { return *group_->lanes_[size_t(lane_)].subscribers; }

FrameContext LaneSource::context_of(const RunGroup::Lane& lane) const {
  return {lane.run_id, lane.seq, lane.scene_version, to_string(group_->lane_status(lane))};
}

std::string LaneSource::snapshot_locked() {
  RunGroup::Lane& lane = group_->lanes_[size_t(lane_)];
  const FrameContext context = context_of(lane);
  std::string frame;
  encode_frame(context, lane.sim->frame(), lane.sim->model(), lane.sim->scene(), *lane.geometry, frame);
  return snapshot_json(context, *lane.sim, frame).dump();
}

std::shared_ptr<FrameSource> RunGroup::source(int lane) {
  return std::make_shared<LaneSource>(shared_from_this(), lane);
}

}  // namespace rrlab::server
