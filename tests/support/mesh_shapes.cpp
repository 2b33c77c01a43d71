#include "support/mesh_shapes.hpp"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <utility>
#include <vector>

namespace rrlab {

namespace {

// A surface of revolution about z from a (radius, z) profile, bottom to top;
// profile ends with radius 0 collapse to poles (degenerate triangles skipped).
TriangleMesh revolve(const std::vector<std::pair<double, double>>& profile, int around) {
  TriangleMesh m;
  for (const auto& [r, z] : profile)
    for (int k = 0; k < around; ++k) {
      const double t = 2 * M_PI * k / around;
      m.vertices.emplace_back(r * std::cos(t), r * std::sin(t), z);
    }
  const int n = int(profile.size());
  for (int i = 0; i + 1 < n; ++i)
    for (int k = 0; k < around; ++k) {
      const int a = i * around + k, b = i * around + (k + 1) % around;
      const int c = a + around, d = b + around;
      if (profile[size_t(i)].first > 0) m.triangles.emplace_back(a, b, d);
      if (profile[size_t(i) + 1].first > 0) m.triangles.emplace_back(a, d, c);
    }
  return m;
}

}  // namespace

TriangleMesh capsule_mesh(double radius, double length, int around, int rings) {
  std::vector<std::pair<double, double>> profile;  // (radius, z) from the bottom pole to the top
  for (int i = 0; i <= rings; ++i) {
    const double a = -M_PI / 2 + M_PI / 2 * i / rings;
    profile.emplace_back(radius * std::cos(a), radius * std::sin(a));
  }
  for (int i = 0; i <= rings; ++i) {
    const double a = M_PI / 2 * i / rings;
    profile.emplace_back(radius * std::cos(a), length + radius * std::sin(a));
  }
  return revolve(profile, around);
}

TriangleMesh sphere_mesh(double radius, int around, int rings) {
  std::vector<std::pair<double, double>> profile;
  for (int i = 0; i <= rings; ++i) {
    const double a = -M_PI / 2 + M_PI * i / rings;
    profile.emplace_back(i == 0 || i == rings ? 0.0 : radius * std::cos(a), radius * std::sin(a));
  }
  return revolve(profile, around);
}

TriangleMesh box_mesh(const Eigen::Vector3d& size) {
  TriangleMesh m;
  const Eigen::Vector3d h = size / 2;
  for (int c = 0; c < 8; ++c)
    m.vertices.emplace_back((c & 1) ? h.x() : -h.x(), (c & 2) ? h.y() : -h.y(), (c & 4) ? h.z() : -h.z());
  // two triangles per face, counter-clockwise seen from outside
  const int faces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                            {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  for (const auto& f : faces) m.triangles.emplace_back(f[0], f[1], f[2]);
  return m;
}

void write_obj(const TriangleMesh& mesh, const std::string& path) {
  std::ofstream out(path);
  out << std::setprecision(17);
  for (const auto& v : mesh.vertices) out << "v " << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
  for (const auto& t : mesh.triangles) out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
}

}  // namespace rrlab
