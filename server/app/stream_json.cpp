#include <rrlab/server/app/stream_json.hpp>

#include <cmath>

#include <rrlab/collision/mesh_loader.hpp>
#include <rrlab/methods/registry_json.hpp>
#include <rrlab/sim/frame_json.hpp>
#include <rrlab/sim/run_inputs.hpp>
#include <rrlab/util/nesting_depth.hpp>
#include <rrlab/util/number_text.hpp>

namespace rrlab::server {

namespace {

// Seven significant digits: enough to draw; exact values come from the REST API.
constexpr int kDrawingDigits = 7;

void num(double v, std::string& out) { append_json_number(v, kDrawingDigits, out); }

template <typename Vec>
void array(const Vec& v, Eigen::Index n, std::string& out) {
  out += '[';
  for (Eigen::Index i = 0; i < n; ++i) {
    if (i) out += ',';
    num(v[i], out);
  }
  out += ']';
}

void key(const char* name, std::string& out) {
  out += ",\"";
  out += name;
  out += "\":";
}

// [[sx,sy,sz,ex,ey,ez], ...]: each link's segment
void link_segments(const Model& model, const KinematicsData& kin, std::string& out) {
  out += '[';
  for (int l = 0; l < model.link_count(); ++l) {
    if (l) out += ',';
    out += '[';
    for (int i = 0; i < 3; ++i) {
      num(kin.link_start(i, l), out);
      out += ',';
    }
    for (int i = 0; i < 3; ++i) {
      num(kin.link_end(i, l), out);
      if (i < 2) out += ',';
    }
    out += ']';
  }
  out += ']';
}

// [[link, obstacle, distance, ax, ay, az, bx, by, bz], ...]: each link's nearest obstacle
void nearest_obstacles(const DistanceTable& distances, std::string& out) {
  out += '[';
  for (int l = 0; l < distances.links; ++l) {
    if (l) out += ',';
    const int o = distances.nearest_obstacle(l);
    const LinkObstacleDistance& pair = distances.at(l, o);
    out += '[';
    out += std::to_string(l + 1);
    out += ',';
    out += std::to_string(o);
    out += ',';
    num(pair.distance, out);
    for (int i = 0; i < 3; ++i) {
      out += ',';
      num(pair.on_link[i], out);
    }
    for (int i = 0; i < 3; ++i) {
      out += ',';
      num(pair.on_obstacle[i], out);
    }
    out += ']';
  }
  out += ']';
}

// {"centre":[x,y,z],"axes":[[..],[..],[..]]}
void ellipsoid_json(const ManipulabilityEllipsoid& e, std::string& out) {
  out += "{\"centre\":";
  array(e.centre, 3, out);
  out += ",\"axes\":[";
  for (int c = 0; c < 3; ++c) {
    if (c) out += ',';
    array(e.axes.col(c), 3, out);
  }
  out += "]}";
}

void overlays(const Overlays& o, const Model& model, FrameGeometry& geometry, std::string& out) {
  out += "{\"ghosts\":[";
  for (size_t i = 0; i < o.ghosts.size(); ++i) {
    if (i) out += ',';
    array(o.ghosts[i], o.ghosts[i].size(), out);
  }
  // each ghost arm's links, so that clients draw it without kinematics
  out += "],\"ghost_links\":[";
  for (size_t i = 0; i < o.ghosts.size(); ++i) {
    if (i) out += ',';
    if (o.ghosts[i].size() == model.dof() && o.ghosts[i].allFinite())
      link_segments(model, geometry.ghost_kinematics(model, o.ghosts[i]), out);
    else
      out += "[]";  // not a configuration of this arm: nothing to draw
  }
  out += "],\"ellipses\":[";
  for (size_t i = 0; i < o.ellipses.size(); ++i) {
    if (i) out += ',';
    out += "{\"centre\":";
    array(o.ellipses[i].centre, 3, out);
    out += ",\"axes\":[";
    for (int c = 0; c < 3; ++c) {
      if (c) out += ',';
      const Eigen::Vector3d axis = o.ellipses[i].axes.col(c);
      array(axis, 3, out);
    }
    out += "]}";
  }
  out += "],\"points\":[";
  for (size_t i = 0; i < o.points.size(); ++i) {
    if (i) out += ',';
    array(o.points[i], 3, out);
  }
  out += "],\"segments\":[";
  for (size_t i = 0; i < o.segments.size(); ++i) {
    if (i) out += ',';
    out += '[';
    array(o.segments[i].first, 3, out);
    out += ',';
    array(o.segments[i].second, 3, out);
    out += ']';
  }
  out += "]}";
}

}  // namespace

void encode_frame(const FrameContext& c, const Frame& f, const Model& model, const Scene& scene,
                  FrameGeometry& geometry, std::string& out) {
  geometry.update(model, scene, c.scene_version, f.q);
  const KinematicsData& kin = geometry.kinematics();
  out.clear();
  out += "{\"type\":\"frame\",\"run\":";
  append_integer(c.run_id, out);
  key("seq", out);
  append_integer(c.seq, out);
  key("status", out);
  out += '"';
  out += c.status;
  out += "\",";
  append_frame_json_members(f, FrameOrigin::live, kDrawingDigits, out);
  key("links", out);
  link_segments(model, kin, out);
  if (model.kind != ModelKind::planar) {
    key("link_quat", out);
    out += '[';
    for (int l = 0; l < model.link_count(); ++l) {
      if (l) out += ',';
      const Eigen::Quaterniond r(kin.joint_frames[size_t(model.links[size_t(l)].last_joint)].linear());
      const double w[4] = {r.w(), r.x(), r.y(), r.z()};
      array(w, 4, out);
    }
    out += ']';
  }
  key("obstacles", out);
  out += '[';
  for (size_t i = 0; i < scene.obstacles.size(); ++i) {
    if (i) out += ',';
    array(scene.obstacles[i].position, 3, out);
  }
  out += ']';
  if (geometry.distances().obstacles > 0) {
    key("nearest", out);
    nearest_obstacles(geometry.distances(), out);
  }
  key("ellipsoid", out);
  ellipsoid_json(geometry.ellipsoid(), out);
  key("scene_version", out);
  append_integer(std::int64_t(c.scene_version), out);
  if (c.wall_us != 0) {
    key("wall_us", out);
    append_integer(c.wall_us, out);
  }
  if (!f.overlays.empty()) {
    key("overlays", out);
    overlays(f.overlays, model, geometry, out);
  }
  out += '}';
}

nlohmann::json model_json(const Model& model) {
  using nlohmann::json;
  json links = json::array();
  for (const Link& l : model.links) links.push_back({{"radius", l.radius}, {"last_joint", l.last_joint + 1}});
  const Eigen::Vector3d base = model.base.translation();
  return {{"kind", to_string(model.kind)},
          {"dof", model.dof()},
          {"base", {base.x(), base.y(), base.z()}},
          {"reach", model.reach()},
          {"links", links},
          {"limits",
           {{"lower", finite_or_null(model.limits.lower)},
            {"upper", finite_or_null(model.limits.upper)},
            {"velocity", finite_or_null(model.limits.velocity)},
            {"acceleration", finite_or_null(model.limits.acceleration)}}}};
}

// A mesh obstacle's triangles for drawing, in its own frame: flat
// [x, y, z, ...] rounded to 1 µm, and flat vertex indices [i, j, k, ...].
// Bounded by ScenarioLimits::max_mesh_obstacle_triangles over the scene.
static nlohmann::json mesh_json(const TriangleMesh& mesh) {
  using nlohmann::json;
  json vertices = json::array(), triangles = json::array();
  for (const Eigen::Vector3d& v : mesh.vertices)
    for (int i = 0; i < 3; ++i) vertices.push_back(std::round(v[i] * 1e6) / 1e6);
  for (const Eigen::Vector3i& t : mesh.triangles)
    for (int i = 0; i < 3; ++i) triangles.push_back(t[i]);
  return {{"vertices", vertices}, {"triangles", triangles}};
}

nlohmann::json snapshot_json(const FrameContext& c, const Simulator& sim, const std::string& frame_text) {
  using nlohmann::json;
  json specs = json::array();
  for (const ParamSpec& spec : sim.method().specs()) specs.push_back(param_spec_json(spec));
  json obstacles = json::array();
  for (const Obstacle& o : sim.scene().obstacles) {
    obstacles.push_back(obstacle_to_json(o));
    if (o.mesh) obstacles.back()["mesh"] = mesh_json(*o.mesh);
  }
  // The path for drawing: the target sampled over the run (empty for a joystick).
  json path = json::array();
  if (!sim.task().is_joystick()) {
    const int samples = 200;
    const double duration = sim.scenario().duration;
    for (int i = 0; i <= samples; ++i) {
      const Eigen::Vector3d p = sim.task().target_position(duration * i / samples);
      path.push_back({p.x(), p.y(), p.z()});
    }
  }
  return {{"type", "snapshot"},
          {"run", c.run_id},
          {"status", c.status},
          {"scenario", sim.scenario().name},
          {"method", sim.method_name()},
          {"dt", sim.scenario().dt},
          {"duration", sim.scenario().duration},
          {"params", param_values_json(sim.method())},
          {"param_specs", specs},
          {"diagnostic_names", sim.diagnostic_names()},
          {"model", model_json(sim.model())},
          {"task",
           {{"space", to_string(sim.scenario().task.space)},
            {"trajectory", to_string(sim.scenario().task.trajectory.type)},
            {"path", path}}},
          {"obstacles", obstacles},
          {"scene_version", c.scene_version},
          {"frame", frame_text.empty() ? json() : parse_json(frame_text)}};
}

nlohmann::json preview_snapshot_json(const Simulator& sim) {
  // as a lane's first snapshot (RunGroup, LaneSource): scene version 1, frame 0
  const FrameContext context{0, 0, 1, "preview"};
  FrameGeometry geometry(sim.model(), sim.scene(), sim.scenario().task.space);
  std::string frame;
  encode_frame(context, sim.frame(), sim.model(), sim.scene(), geometry, frame);
  nlohmann::json snapshot = snapshot_json(context, sim, frame);
  snapshot["run"] = nullptr;
  snapshot["frame"]["run"] = nullptr;
  snapshot["preview"] = true;
  return snapshot;
}

nlohmann::json params_message_json(const FrameContext& c, const Simulator& sim) {
  return {{"type", "params"},
          {"run", c.run_id},
          {"scene_version", c.scene_version},
          {"params", param_values_json(sim.method())}};
}

nlohmann::json scene_message_json(const FrameContext& c, const Simulator& sim) {
  nlohmann::json obstacles = nlohmann::json::array();
  for (const Obstacle& o : sim.scene().obstacles) obstacles.push_back(obstacle_to_json(o));
  return {{"type", "scene"}, {"run", c.run_id}, {"scene_version", c.scene_version}, {"obstacles", obstacles}};
}

}  // namespace rrlab::server
