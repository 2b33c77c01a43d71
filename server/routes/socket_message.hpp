// The WebSocket route's messages: a client's message to a live run or a
// replay, parsed here into the app's typed commands (a live lane:
// RunGroup::control and RunGroup::input; a replay: ReplayPlayer::control)
// and answered without a socket (net/websocket_session.cpp sends the reply;
// the fuzzer of tests/fuzz/ calls it directly).
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include <rrlab/server/app/frame_source.hpp>
#include <rrlab/storage/completion.hpp>

namespace rrlab::server {

// The reply to a client message: sent at once, or, when `pending` is set,
// once it settles (an input's event stored, a single step taken): then the
// ack carries the settled status, or an error if the work failed (settled_reply).
struct MessageReply {
  nlohmann::json reply;
  std::shared_ptr<storage::Completion> pending;
};

// The reply to one message: an ack or an error ({"type": "error", ...}),
// never an exception; an ack that waits for stored input or a step has
// `pending` set (send settled_reply(reply.reply, outcome) once it settles). `client` is the
// connection's client name (app/controller.hpp); `may_steer` is false for a
// watch-only connection (a server with a token, a client without it).
MessageReply reply_to_socket_message(FrameSource& source, const std::string& client, bool may_steer,
                                     const std::string& text);

// The message to send once a reply's pending work has settled with `outcome`
// (`ack` is the reply: {"type": "ack", "status": ...}).
nlohmann::json settled_reply(const nlohmann::json& ack, const storage::Outcome& outcome);

}  // namespace rrlab::server
