#include <rrlab/generators/generator_furniture.hpp>

#include <Eigen/Geometry>
#include <cmath>

#include <rrlab/generators/generator_case.hpp>

namespace rrlab {

namespace {
constexpr int kFurnitureCylinderSides = 12;
constexpr double kFurnitureStep = 1e-4;  // m, rad: coordinates as furniture_written

Eigen::Matrix3d furniture_about_z(double yaw) { return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix(); }
nlohmann::json furniture_written(const Eigen::Vector3d& v) { return {rounded(v.x(), kFurnitureStep), rounded(v.y(), kFurnitureStep), rounded(v.z(), kFurnitureStep)}; }
}  // namespace

Eigen::Vector3d FloorFrame::world(const Eigen::Vector3d& local) const { return origin + furniture_about_z(yaw) * local; }
Eigen::Vector3d FloorFrame::local(const Eigen::Vector3d& world) const { return furniture_about_z(yaw).transpose() * (world - origin); }

nlohmann::json frame_box(const std::string& id, const FloorFrame& frame, const Eigen::Vector3d& center,
                         const Eigen::Vector3d& size, double yaw) {
  return {{"id", id},
          {"shape", "box"},
          {"center", furniture_written(frame.world(center))},
          {"size", furniture_written(size)},
          {"rpy", {0.0, 0.0, rounded(frame.yaw + yaw, kFurnitureStep)}}};
}

nlohmann::json frame_cylinder(const std::string& id, const FloorFrame& frame, const Eigen::Vector3d& base,
                              double radius, double height) {
  nlohmann::json points = nlohmann::json::array();
  const Eigen::Vector3d centre = frame.world(base);
  for (int k = 0; k < kFurnitureCylinderSides; ++k) {
    const double a = 2 * M_PI * k / kFurnitureCylinderSides;
    points.push_back({rounded(centre.x() + radius * std::cos(a), kFurnitureStep), rounded(centre.y() + radius * std::sin(a), kFurnitureStep)});
  }
  return {{"id", id},
          {"shape", "polygon"},
          {"points", points},
          {"z", {rounded(centre.z(), kFurnitureStep), rounded(centre.z() + height, kFurnitureStep)}}};
}

}  // namespace rrlab
