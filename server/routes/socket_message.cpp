#include <rrlab/server/routes/socket_message.hpp>

#include <rrlab/scenario/json_reader.hpp>
#include <rrlab/server/api/errors.hpp>
#include <rrlab/server/api/request.hpp>
#include <rrlab/server/app/controller.hpp>
#include <rrlab/server/app/lane_source.hpp>
#include <rrlab/server/app/replay_player.hpp>
#include <rrlab/server/routes/http_errors.hpp>
#include <rrlab/server/routes/routes.hpp>

namespace rrlab::server {

using nlohmann::json;

namespace {

// An error reply, carried out of Controller::steer so that it lets go of the control it took.
struct RefusedMessage {
  json reply;
};

// {"type": "input", "kind", "payload"?}: errors name paths under "payload"
// (the kind's: "payload.kind").
Accepted input_message(LaneSource& source, JsonObject& message, const json& raw) {
  const std::string name = message.string("kind");
  const std::optional<InputKind> kind = parse_input_kind(name);
  if (!kind) throw DomainError(Problem::invalid, "invalid", unknown_input_kind(name).what(), "payload.kind");
  try {
    return source.group().input(source.lane(), *kind, raw.value("payload", json::object()));
  } catch (const DomainError& e) {
    throw e.under("payload");
  }
}

// A live lane's message: {"type": "control", "action"?, "rate"?} or {"type": "input", ...}.
MessageReply live_message(LaneSource& source, const json& message) {
  source.group().touch();
  std::shared_ptr<storage::Completion> pending;
  json reply = socket_reply([&]() -> json {
    JsonObject obj(message, "");
    const std::string type = obj.choice("type", {"input", "control"});
    Accepted accepted;
    if (type == "control") {
      obj.check_keys({"type", "action", "rate"});
      json body = message;
      body.erase("type");
      accepted = source.group().control(source.lane(), parse_control_command(body));
    } else {
      obj.check_keys({"type", "kind", "payload"});
      accepted = input_message(source, obj, message);
    }
    pending = std::move(accepted.pending);
    return std::move(accepted.status);
  });
  return {std::move(reply), std::move(pending)};
}

// A replay's message: {"type": "control", "action"?, "seq"?, "speed"?}.
MessageReply replay_message(ReplayPlayer& player, const json& message) {
  return {socket_reply([&] {
            if (!message.is_object() || message.value("type", "") != "control")
              throw DomainError(Problem::invalid, "invalid",
                                "a replay takes {\"type\": \"control\", \"action\": play|pause|seek}", "type");
            json body = message;
            body.erase("type");
            return player.control(parse_replay_command(body));
          }),
          nullptr};
}

// The message to the source it was sent to (the WebSocket routes make live lanes and replays).
MessageReply handle_message(FrameSource& source, const json& message) {
  if (auto* lane = dynamic_cast<LaneSource*>(&source)) return live_message(*lane, message);
  if (auto* player = dynamic_cast<ReplayPlayer*>(&source)) return replay_message(*player, message);
  return {socket_error(DomainError(Problem::invalid, "invalid", "this stream takes no messages", "type")), nullptr};
}

}  // namespace

json settled_reply(const json& ack, const storage::Outcome& outcome) {
  return socket_reply([&] { return settled_status(ack.at("status"), outcome, "payload"); });
}

MessageReply reply_to_socket_message(FrameSource& source, const std::string& client, bool may_steer,
                                     const std::string& text) {
  try {
    const json message = parse_client_json(text);
    if (!may_steer)
      throw DomainError(Problem::unauthorized, "unauthorized",
                        "this connection watches only: reconnect with the token (query parameter token=TOKEN) to steer");
    if (Controller* controller = source.controller()) {
      const std::string action =
          message.is_object() && message.value("type", json()) == "control" && message.contains("action") &&
                  message["action"].is_string()
              ? message["action"].get<std::string>()
              : "";
      if (action == "take" || action == "release") {
        if (message.size() != 2)
          throw DomainError(Problem::invalid, "invalid", "take and release take no other keys", "action");
        return {{{"type", "ack"}, {"status", action == "take" ? controller->take(client) : controller->release(client)}},
                nullptr};
      }
      // an error is answered as a reply; only an ack keeps the control it took
      return controller->steer(client, [&] {
        MessageReply reply = handle_message(source, message);
        if (reply.reply.value("type", "") != "ack") throw RefusedMessage{std::move(reply.reply)};
        return reply;
      });
    }
    return handle_message(source, message);
  } catch (RefusedMessage& refused) {
    return {std::move(refused.reply), nullptr};
  } catch (const DomainError& e) {
    return {socket_error(e), nullptr};
  } catch (const std::exception&) {
    return {socket_error(DomainError(Problem::internal, "internal", "the message could not be handled")), nullptr};
  }
}

}  // namespace rrlab::server
