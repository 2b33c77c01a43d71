// Messages of the WebSocket stream. Frames are written by hand (not through
// nlohmann::json) because they are encoded up to 60 times a second per run:
// numbers carry 7 significant digits, enough to draw; exact values come from
// GET /api/runs/{id}/frames.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include <rrlab/server/app/frame_geometry.hpp>
#include <rrlab/sim/frame.hpp>
#include <rrlab/sim/simulator.hpp>

namespace rrlab::server {

struct FrameContext {
  std::int64_t run_id = 0, seq = 0;
  std::uint64_t scene_version = 0;
  const char* status = "running";
  std::int64_t wall_us = 0;  // publication time (system clock, µs): clients measure latency; 0: omitted
};

// {"type":"frame","run","seq","status", then the frame's fields as every JSON
//  frame has them (sim/frame_json.hpp: "step","t","q","qdot","ee","ee_quat","target",
//  "target_quat" (pose tasks),"metrics":{..,"step_us"},"diagnostics":[..]), then
//  "links":[[sx,sy,sz,ex,ey,ez],..],"link_quat":[[w,x,y,z],..] (3D models),"obstacles":[[x,y,z],..],
//  "nearest":[[link,obstacle,distance,ax,ay,az,bx,by,bz],..] (one per link, its nearest
//    obstacle: link 1-based, obstacle a 0-based index into the snapshot's obstacles, signed
//    distance, a on the link axis, b on the obstacle surface; omitted without obstacles),
//  "ellipsoid":{"centre":[x,y,z],"axes":[[..],[..],[..]]} (velocity manipulability ellipsoid of
//    the task Jacobian's position rows: semi-axes σ_i·u_i, longest first, zero when missing),
//  "scene_version","wall_us" (when set),
//  "overlays":{"ghosts":[q,..],"ghost_links":[[[sx,sy,sz,ex,ey,ez],..],..],"ellipses","points","segments"}
//    (only when the method draws something; ghost_links: each ghost's links, as "links")}
// Links, nearest and ellipsoid come from `geometry`, updated here at frame.q
// with the scene as it is now. Non-finite numbers are written as null.
void encode_frame(const FrameContext& context, const Frame& frame, const Model& model, const Scene& scene,
                  FrameGeometry& geometry, std::string& out);

// The model for drawing: kind, dof, link radii, joint limits, base.
nlohmann::json model_json(const Model& model);
// {"type":"snapshot", run, scenario, method, status, params, param_specs, diagnostic_names,
//  model, task {space, path}, obstacles, scene_version, frame}
nlohmann::json snapshot_json(const FrameContext& context, const Simulator& sim, const std::string& frame_text);
// The snapshot a run's stream would start with, of a simulator just built and
// of no run (GET /api/scenarios/{name}/preview): its frame 0 encoded as a
// lane's (links, nearest, ellipsoid), "run": null, "status": "preview",
// "preview": true. Stores nothing; the cost of one frame's geometry.
nlohmann::json preview_snapshot_json(const Simulator& sim);
// What changed without a new snapshot: {"type":"params", run, scene_version,
// params} after a parameter change; {"type":"scene", run, scene_version,
// obstacles} after an obstacle edit (obstacles in scenario syntax, without a
// mesh obstacle's triangles, which an edit does not change: the client keeps
// those of its snapshot, by obstacle id).
nlohmann::json params_message_json(const FrameContext& context, const Simulator& sim);
nlohmann::json scene_message_json(const FrameContext& context, const Simulator& sim);

}  // namespace rrlab::server
