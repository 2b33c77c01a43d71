#include <rrlab/urdf/urdf_chain.hpp>

#include <tinyxml.h>

#include <cmath>
#include <console_bridge/console.h>
#include <limits>
#include <map>
#include <mutex>
#include <set>
#include <urdf_parser/urdf_parser.h>

#include <rrlab/util/nesting_depth.hpp>

namespace rrlab {

namespace {

std::string in_quotes(const std::string& s) { return "'" + s + "'"; }

// urdfdom gives its reasons for refusing a document only to console_bridge's
// output handler (stderr by default). This handler, installed once for the
// process, keeps the errors logged by the calling thread's parse instead, so
// the UrdfError can quote them, and keeps urdfdom's console noise out of the
// server's log. Other threads' messages (none but urdfdom's are expected)
// are dropped.
class CapturingHandler : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (capture_ && level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) {
      std::string line = text;
      while (!line.empty() && (line.back() == '\n' || line.back() == ' ')) line.pop_back();
      if (!line.empty()) *capture_ += (capture_->empty() ? "" : "; ") + line;
    }
  }
  // Collects the errors logged by this thread while it exists.
  struct Scope {
    explicit Scope(std::string& into) { capture_ = &into; }
    ~Scope() { capture_ = nullptr; }
  };

 private:
  static inline thread_local std::string* capture_ = nullptr;
};

urdf::ModelInterfaceSharedPtr parse_with_urdfdom(const std::string& xml, std::string& errors) {
  static std::once_flag installed;
  // never destroyed: console_bridge keeps the pointer until the process ends
  std::call_once(installed, [] { console_bridge::useOutputHandler(new CapturingHandler); });
  CapturingHandler::Scope scope(errors);
  return urdf::parseURDF(xml);
}

// urdfdom reports why it rejects a document only on its console; the checks
// below find the common faults first so the error can name them: XML that is
// not well formed, a joint naming a link that is not defined, a link with two
// parents, and a cycle.
void check_structure(const std::string& xml) {
  if (xml.find_first_not_of(" \t\r\n") == std::string::npos) throw UrdfError("the URDF is empty");
  // TinyXML recurses once per element level: refuse deep documents before it runs.
  if (const auto at = xml_too_deep_at(xml)) throw UrdfError(TooDeepError("XML", kMaxXmlDepth, *at).what());
  TiXmlDocument doc;
  doc.Parse(xml.c_str());
  if (doc.Error())
    throw UrdfError("malformed XML at line " + std::to_string(doc.ErrorRow()) + ", column " +
                    std::to_string(doc.ErrorCol()) + ": " + doc.ErrorDesc());
  const TiXmlElement* robot = doc.FirstChildElement("robot");
  if (!robot) throw UrdfError("not a URDF: no <robot> element");
  std::set<std::string> links;
  for (const TiXmlElement* l = robot->FirstChildElement("link"); l; l = l->NextSiblingElement("link")) {
    const char* name = l->Attribute("name");
    if (!name) throw UrdfError("a <link> has no name (line " + std::to_string(l->Row()) + ")");
    if (!links.insert(name).second) throw UrdfError("link " + in_quotes(name) + " is defined twice");
    if (links.size() > kMaxUrdfLinks)
      throw UrdfError("the URDF has more than " + std::to_string(kMaxUrdfLinks) + " links");
  }
  std::size_t joints = 0;
  std::map<std::string, std::string> parent_of, joint_of;  // child link -> parent link / joint
  for (const TiXmlElement* j = robot->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) {
    const char* name = j->Attribute("name");
    if (!name) throw UrdfError("a <joint> has no name (line " + std::to_string(j->Row()) + ")");
    if (++joints > kMaxUrdfJoints)
      throw UrdfError("the URDF has more than " + std::to_string(kMaxUrdfJoints) + " joints");
    const std::string joint = name;
    auto link_of = [&](const char* element) -> std::string {
      const TiXmlElement* e = j->FirstChildElement(element);
      const char* link = e ? e->Attribute("link") : nullptr;
      if (!link) throw UrdfError("joint " + in_quotes(joint) + " has no <" + element + " link=\"...\">");
      if (!links.count(link))
        throw UrdfError("joint " + in_quotes(joint) + " names " + element + " link " + in_quotes(link) +
                        ", which is not defined");
      return link;
    };
    const std::string parent = link_of("parent"), child = link_of("child");
    if (parent == child) throw UrdfError("joint " + in_quotes(joint) + " connects link " + in_quotes(child) + " to itself");
    if (joint_of.count(child))
      throw UrdfError("link " + in_quotes(child) + " is the child of two joints (" + in_quotes(joint_of[child]) + " and " +
                      in_quotes(joint) + ")");
    parent_of[child] = parent;
    joint_of[child] = joint;
  }
  // Each link has at most one parent, so walking up from every link finds any
  // cycle. A walk stops at a link an earlier walk finished (linear in links):
  // meeting a link of its own walk again closes a cycle.
  std::map<std::string, std::size_t> walk_of;  // link -> the walk that reached it first
  std::size_t walk = 0;
  for (const std::string& start : links) {
    if (walk_of.count(start)) continue;
    ++walk;
    walk_of[start] = walk;
    for (auto it = parent_of.find(start); it != parent_of.end(); it = parent_of.find(it->second)) {
      const auto [seen, first_time] = walk_of.emplace(it->second, walk);
      if (first_time) continue;
      if (seen->second == walk)
        throw UrdfError("the joints form a cycle through link " + in_quotes(it->second) + " (joint " +
                        in_quotes(joint_of[it->second]) + ")");
      break;  // an earlier walk went on from here
    }
  }
}

Eigen::Isometry3d to_isometry(const urdf::Pose& p) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z).normalized().toRotationMatrix();
  t.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  return t;
}

// The radius of a capsule standing in for one collision primitive: a sphere's
// or a cylinder's radius; a box, half its middle edge (the capsule runs along
// the longest edge and the smallest is covered). -1 for a mesh.
double primitive_radius(const urdf::Geometry& g) {
  switch (g.type) {
    case urdf::Geometry::SPHERE: return static_cast<const urdf::Sphere&>(g).radius;
    case urdf::Geometry::CYLINDER: return static_cast<const urdf::Cylinder&>(g).radius;
    case urdf::Geometry::BOX: {
      const urdf::Vector3& d = static_cast<const urdf::Box&>(g).dim;
      double e[3] = {d.x, d.y, d.z};
      std::sort(e, e + 3);
      return e[1] / 2;
    }
    default: return -1;
  }
}

}  // namespace

// Stays whole (over 100 lines): the chain from base to tip is walked once,
// each joint checked and converted where it is met.
UrdfChain read_urdf_chain(const std::string& xml, const std::string& base_link, const std::string& tip_link) {
  check_structure(xml);
  std::string urdfdom_errors;
  const urdf::ModelInterfaceSharedPtr model = parse_with_urdfdom(xml, urdfdom_errors);
  if (!model)
    throw UrdfError("urdfdom rejected the URDF: " +
                    (urdfdom_errors.empty() ? std::string("(it gave no reason)") : urdfdom_errors));
  if (!model->getRoot()) throw UrdfError("the URDF has no root link");

  UrdfChain chain;
  chain.base_link = base_link.empty() ? model->getRoot()->name : base_link;
  if (!model->getLink(chain.base_link)) throw UrdfError("base_link " + in_quotes(chain.base_link) + " is not a link of the URDF", "base_link");
  chain.tip_link = tip_link;
  if (tip_link.empty()) {
    std::vector<urdf::LinkSharedPtr> links;
    model->getLinks(links);
    std::vector<std::string> leaves;
    for (const auto& l : links)
      if (l->child_joints.empty()) leaves.push_back(l->name);
    if (leaves.size() != 1) {
      std::string names;
      for (const auto& n : leaves) names += (names.empty() ? "" : ", ") + in_quotes(n);
      throw UrdfError("the URDF has " + std::to_string(leaves.size()) + " leaf links (" + names + "); name the tip_link",
                      "tip_link");
    }
    chain.tip_link = leaves.front();
  }
  urdf::LinkConstSharedPtr tip = model->getLink(chain.tip_link);
  if (!tip) throw UrdfError("tip_link " + in_quotes(chain.tip_link) + " is not a link of the URDF", "tip_link");

  // Walk up from the tip to the base, then read the joints base to tip.
  std::vector<urdf::LinkConstSharedPtr> path;  // tip ... (child of base)
  for (urdf::LinkConstSharedPtr l = tip; l->name != chain.base_link;) {
    path.push_back(l);
    l = l->getParent();
    if (!l) throw UrdfError("tip_link " + in_quotes(chain.tip_link) + " is not below base_link " + in_quotes(chain.base_link) +
                      " (base_link must be an ancestor of tip_link)",
                      "tip_link");
  }
  std::reverse(path.begin(), path.end());

  constexpr double inf = std::numeric_limits<double>::infinity();
  std::vector<double> lower, upper, velocity;
  Eigen::Isometry3d pending = Eigen::Isometry3d::Identity();  // fixed transforms since the last moving joint
  double radius = -1;                                         // of the current segment's links
  std::vector<UrdfMesh> meshes;
  auto close_segment = [&] {
    if (chain.joints.empty()) return;
    chain.joints.back().radius = radius;
    chain.meshes.push_back(meshes);
  };
  for (const urdf::LinkConstSharedPtr& link : path) {
    const urdf::Joint& j = *link->parent_joint;
    const std::string name = in_quotes(j.name);
    if (j.mimic) throw UrdfError("joint " + name + " is a mimic joint (of " + in_quotes(j.mimic->joint_name) + "); mimic joints are not supported");
    if (j.type == urdf::Joint::FLOATING || j.type == urdf::Joint::PLANAR)
      throw UrdfError("joint " + name + " is a " + (j.type == urdf::Joint::FLOATING ? "floating" : "planar") +
                      " joint; only revolute, continuous, prismatic and fixed joints are supported");
    if (j.type == urdf::Joint::UNKNOWN) throw UrdfError("joint " + name + " has an unknown type");
    pending = pending * to_isometry(j.parent_to_joint_origin_transform);
    if (j.type != urdf::Joint::FIXED) {
      close_segment();
      ChainJointSpec spec;
      spec.type = j.type == urdf::Joint::PRISMATIC ? JointType::prismatic : JointType::revolute;
      spec.origin = pending;
      const Eigen::Vector3d axis(j.axis.x, j.axis.y, j.axis.z);
      if (!(axis.norm() > 1e-9)) throw UrdfError("joint " + name + " has a zero axis");
      spec.axis = axis.normalized();
      chain.joints.push_back(spec);
      chain.joint_names.push_back(j.name);
      const bool bounded = j.type != urdf::Joint::CONTINUOUS && j.limits;
      const double lo = bounded ? j.limits->lower : -inf, hi = bounded ? j.limits->upper : inf;
      if (bounded && !(lo < hi))
        throw UrdfError("joint " + name + " has lower limit " + std::to_string(lo) + " not below upper " + std::to_string(hi));
      lower.push_back(lo);
      upper.push_back(hi);
      velocity.push_back(j.limits && j.limits->velocity > 0 ? j.limits->velocity : inf);
      pending = Eigen::Isometry3d::Identity();
      radius = -1;
      meshes.clear();
    }
    // Collision primitives of this link count for the segment it belongs to.
    // Fixed links before the first moving joint belong to the pedestal.
    for (const auto& c : link->collision_array) {
      if (!c || !c->geometry) continue;
      const double r = primitive_radius(*c->geometry);
      if (c->geometry->type == urdf::Geometry::MESH && !chain.joints.empty()) {
        const auto& m = static_cast<const urdf::Mesh&>(*c->geometry);
        meshes.push_back({link->name, m.filename, Eigen::Vector3d(m.scale.x, m.scale.y, m.scale.z),
                          pending * to_isometry(c->origin)});
      }
      radius = std::max(radius, r);
    }
  }
  if (chain.joints.empty())
    throw UrdfError("no revolute, continuous or prismatic joint between " + in_quotes(chain.base_link) + " and " + in_quotes(chain.tip_link));
  close_segment();
  chain.tip = pending;
  const int n = static_cast<int>(chain.joints.size());
  chain.limits = unbounded_limits(n);
  for (int i = 0; i < n; ++i) {
    chain.limits.lower[i] = lower[i];
    chain.limits.upper[i] = upper[i];
    chain.limits.velocity[i] = velocity[i];
  }
  return chain;
}

}  // namespace rrlab
