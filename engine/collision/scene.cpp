#include <rrlab/collision/scene.hpp>

namespace rrlab {

const char* to_string(ShapeKind kind) {
  switch (kind) {
    case ShapeKind::polygon: return "polygon";
    case ShapeKind::box: return "box";
    case ShapeKind::sphere: return "sphere";
    case ShapeKind::point: return "point";
    case ShapeKind::wall: return "wall";
    case ShapeKind::mesh: return "mesh";
  }
  return "?";
}

int Scene::find(const std::string& id) const {
  for (size_t i = 0; i < obstacles.size(); ++i)
    if (obstacles[i].id == id) return static_cast<int>(i);
  return -1;
}

void Scene::advance_to(double t) {
  for (Obstacle& o : obstacles) o.position = o.position0 + o.velocity * t;
}

}  // namespace rrlab
