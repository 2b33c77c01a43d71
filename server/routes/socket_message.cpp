#include <rrlab/server/app/socket_message.hpp>

#include <rrlab/server/app/controller.hpp>
#include <rrlab/server/routes/api.hpp>

namespace rrlab::server {

namespace {
// An error reply, carried out of Controller::steer so that it lets go of the control it took.
struct RefusedMessage {
  nlohmann::json reply;
};
}  // namespace

nlohmann::json settled_reply(const nlohmann::json& ack, const storage::Outcome& outcome) {
  return socket_reply([&] { return settled_status(ack.at("status"), outcome, "payload"); });
}

MessageReply reply_to_socket_message(FrameSource& source, const std::string& client, bool may_steer,
                                       const std::string& text) {
  try {
    const nlohmann::json message = parse_client_json(text);
    if (!may_steer)
      throw ApiError(401, "unauthorized",
                     "this connection watches only: reconnect with the token (query parameter token=TOKEN) to steer");
    if (Controller* controller = source.controller()) {
      const std::string action =
          message.is_object() && message.value("type", nlohmann::json()) == "control" && message.contains("action") &&
                  message["action"].is_string()
              ? message["action"].get<std::string>()
              : "";
      if (action == "take" || action == "release") {
        if (message.size() != 2) throw ApiError(400, "invalid", "take and release take no other keys", "action");
        return {{{"type", "ack"}, {"status", action == "take" ? controller->take(client) : controller->release(client)}},
                nullptr};
      }
      // handle_message answers errors as a reply; only an ack keeps the control it took
      return controller->steer(client, [&] {
        MessageReply reply = source.handle_message(message);
        if (reply.reply.value("type", "") != "ack") throw RefusedMessage{std::move(reply.reply)};
        return reply;
      });
    }
    return source.handle_message(message);
  } catch (RefusedMessage& refused) {
    return {std::move(refused.reply), nullptr};
  } catch (const ApiError& e) {
    return {socket_error(e), nullptr};
  } catch (const std::exception&) {
    return {socket_error(ApiError(500, "internal", "the message could not be handled")), nullptr};
  }
}

}  // namespace rrlab::server
