// Inputs to a live run: control, parameters, obstacles, joystick, method.
// Each is validated (400 naming the field, 409 in the wrong state or when
// another client controls the run: app/controller.hpp), applied, and
// answered once stored as an event with the step at which it takes effect
// (the frame writer stores it; no I/O thread waits for SQLite).
#include <rrlab/server/routes/routes.hpp>
#include <rrlab/storage/completion.hpp>

namespace rrlab::server {

using nlohmann::json;

namespace {
// The answer to an accepted input or control: at once, or once the work it
// waits for settles (its event stored, its step taken), without holding an
// I/O thread meanwhile.
ApiResponse answer(Accepted accepted) {
  if (!accepted.pending) return json_response(200, accepted.status);
  ApiResponse response;
  response.deferred = [accepted = std::move(accepted)](Responder respond) {
    accepted.pending->then([status = accepted.status, respond](const storage::Outcome& outcome) {
      try {
        respond(json_response(200, settled_status(status, outcome, "")));
      } catch (const DomainError& e) {
        respond(error_response(e));
      }
    });
  };
  return response;
}

ApiResponse apply(RouteContext& c, InputKind kind, const json& payload) {
  int lane = 0;
  auto group = live_group(c, c.id(), lane);
  return group->controller().steer(c.request.client, [&] { return answer(group->input(lane, kind, payload)); });
}
// An input to the obstacle named in the path: an unknown one is a missing resource (404).
ApiResponse apply_to_obstacle(RouteContext& c, InputKind kind, const json& payload) {
  try {
    return apply(c, kind, payload);
  } catch (const DomainError& e) {
    if (e.path() == "id" && e.problem() == Problem::invalid)
      throw DomainError(Problem::not_found, "not_found", e.what(), "obstacle");
    throw;
  }
}
}  // namespace

ControlCommand parse_control_command(const json& body) {
  ControlCommand command;
  try {
    JsonObject obj(body, "");
    obj.check_keys({"action", "rate"});
    if (obj.has("action"))
      command.action = parse_control_action(obj.choice("action", {"start", "pause", "step", "reset", "stop"})).value();
    command.rate = obj.optional_number("rate");
  } catch (...) {
    rethrow_as_domain_error("");
  }
  return command;
}

ApiResponse post_control(RouteContext& c) {
  const json body = parse_body(c.request);
  int lane = 0;
  auto group = live_group(c, c.id(), lane);
  // {"action": "take" | "release"}: control of the run (app/controller.hpp)
  const std::string action = body.is_object() && body.contains("action") && body["action"].is_string()
                                 ? body["action"].get<std::string>()
                                 : "";
  if (action == "take" || action == "release") {
    if (body.size() != 1)
      throw DomainError(Problem::invalid, "invalid", "take and release take no other keys", "action");
    Controller& controller = group->controller();
    const std::string& client = c.request.client;
    return json_response(200, action == "take" ? controller.take(client) : controller.release(client));
  }
  // parsed within steer: a refused body takes no control
  ControlCommand command;
  Accepted accepted = group->controller().steer(c.request.client, [&] {
    command = parse_control_command(body);
    return group->control(lane, command);
  });
  if (command.action == ControlAction::stop) {
    // answer once the run has ended and its frames are committed
    ApiResponse response;
    response.deferred = [group, lane](Responder respond) {
      group->when_finished([group, lane, respond] { respond(json_response(200, group->status_json(lane))); });
    };
    return response;
  }
  return answer(std::move(accepted));
}

ApiResponse patch_params(RouteContext& c) { return apply(c, InputKind::params, parse_body(c.request)); }

ApiResponse put_obstacle(RouteContext& c) {
  json payload = parse_body(c.request);
  if (!payload.is_object()) throw DomainError(Problem::invalid, "invalid", "the body must be a JSON object");
  if (payload.contains("id") && payload["id"] != c.captures.at(1))
    throw DomainError(Problem::invalid, "invalid", "differs from the obstacle id in the path", "id");
  payload["id"] = c.captures.at(1);
  return apply_to_obstacle(c, InputKind::obstacle, payload);
}

ApiResponse post_obstacle(RouteContext& c) { return apply(c, InputKind::obstacle_add, parse_body(c.request)); }

ApiResponse delete_obstacle(RouteContext& c) {
  return apply_to_obstacle(c, InputKind::obstacle_remove, {{"id", c.captures.at(1)}});
}

ApiResponse post_joystick(RouteContext& c) { return apply(c, InputKind::joystick, parse_body(c.request)); }

ApiResponse post_method(RouteContext& c) { return apply(c, InputKind::method, parse_body(c.request)); }

}  // namespace rrlab::server
