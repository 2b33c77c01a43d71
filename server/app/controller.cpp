#include <rrlab/server/app/controller.hpp>

#include <cctype>
#include <vector>

#include <rrlab/server/api/errors.hpp>

namespace rrlab::server {

using nlohmann::json;

std::string valid_client_name(const std::string& name) {
  if (name.empty() || name.size() > 64) return "";
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '-')) return "";
  return name;
}

json Controller::state_message_locked(const std::string& client) const {
  json message = state_locked(client);
  message["type"] = "control";
  message["event"] = "state";
  return message;
}

Controller::Notices Controller::state_notices_locked() const {
  Notices notices;
  for (const auto& [id, c] : connections_)
    if (c.notify) notices.emplace_back(c.notify, state_message_locked(c.client));
  return notices;
}

void Controller::send(const Notices& notices) {
  for (const auto& [notify, message] : notices) notify(message);
}

std::uint64_t Controller::attach(const std::string& client, Notify notify) {
  Notices notices;
  std::uint64_t handle = 0;
  {
    std::lock_guard lock(mutex_);
    handle = ++next_;
    const bool lapsed = lapse_locked();
    connections_[handle] = Connection{client, notify};
    if (lapsed) notices = state_notices_locked();  // everyone: control lapsed
    else if (notify) notices.emplace_back(std::move(notify), state_message_locked(client));
  }
  send(notices);
  return handle;
}

void Controller::detach(std::uint64_t connection) {
  Notices notices;
  {
    std::lock_guard lock(mutex_);
    const auto it = connections_.find(connection);
    if (it == connections_.end()) return;
    const std::string client = it->second.client;
    connections_.erase(it);
    if (client != holder_) return;
    for (const auto& [id, c] : connections_)
      if (c.client == client) return;  // the holder has another connection (another lane of a compare)
    holder_.clear();
    notices = state_notices_locked();
  }
  send(notices);
}

bool Controller::lapse_locked() {
  if (holder_.empty() || now_() - holder_seen_ <= lapse_) return false;
  for (const auto& [id, c] : connections_)
    if (c.client == holder_) return false;  // a holder with a WebSocket keeps control until it closes
  holder_.clear();
  return true;
}

bool Controller::hold(const std::string& client) {
  if (client.empty()) return false;
  Notices notices;  // of a lapse found now
  bool fresh = false, refused = false;
  {
    std::lock_guard lock(mutex_);
    if (lapse_locked()) notices = state_notices_locked();
    if (holder_ == client) {
      holder_seen_ = now_();
    } else if (holder_.empty()) {
      holder_ = client;
      holder_seen_ = now_();
      fresh = true;
    } else {
      refused = true;
    }
  }
  send(notices);
  if (refused)
    throw DomainError(Problem::conflict, "not_controller",
                      "another client controls this run; you are watching. Take control with "
                      "{\"type\": \"control\", \"action\": \"take\"} (WebSocket) or "
                      "POST /api/runs/{id}/control {\"action\": \"take\"} with an Rrlab-Client header naming you");
  return fresh;
}

void Controller::announce() {
  Notices notices;
  {
    std::lock_guard lock(mutex_);
    notices = state_notices_locked();
  }
  send(notices);
}

void Controller::unhold(const std::string& client) {
  std::lock_guard lock(mutex_);
  if (holder_ == client) holder_.clear();
}

json Controller::take(const std::string& client) {
  if (client.empty())
    throw DomainError(Problem::invalid, "invalid",
                      "taking control needs a client name: the Rrlab-Client header (REST) or the client query "
                      "parameter (WebSocket)",
                      "action");
  std::vector<Notify> previous;  // called unlocked: a notification may end its session
  Notices notices;
  json state;
  {
    std::lock_guard lock(mutex_);
    if (!holder_.empty() && holder_ != client)
      for (const auto& [id, c] : connections_)
        if (c.client == holder_ && c.notify) previous.push_back(c.notify);
    lapse_locked();
    const bool changed = holder_ != client;
    holder_ = client;
    holder_seen_ = now_();
    if (changed) notices = state_notices_locked();
    state = state_locked(client);
  }
  const json taken = {{"type", "control"},
                      {"event", "taken"},
                      {"controller", "other"},
                      {"message", "another client took control of this run; you are watching now"}};
  for (const Notify& notify : previous) notify(taken);
  send(notices);
  return state;
}

json Controller::release(const std::string& client) {
  Notices notices;
  json state;
  {
    std::lock_guard lock(mutex_);
    if (!client.empty() && holder_ == client) {
      holder_.clear();
      notices = state_notices_locked();
    }
    state = state_locked(client);
  }
  send(notices);
  return state;
}

json Controller::state_json(const std::string& client) {
  Notices notices;
  json state;
  {
    std::lock_guard lock(mutex_);
    if (lapse_locked()) notices = state_notices_locked();
    state = state_locked(client);
  }
  send(notices);
  return state;
}

json Controller::state_locked(const std::string& client) const {
  return {{"controller", holder_.empty() ? "none" : holder_ == client ? "you" : "other"}};
}

}  // namespace rrlab::server
