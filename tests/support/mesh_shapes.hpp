// Triangle meshes of simple solids, generated (no file): the fixtures of the
// mesh tests and benchmarks, and a way to compare a mesh against the
// analytic shape it approximates. Outward-facing, counter-clockwise triangles.
// Test code, not the engine's: compiled into the engine tests and the
// benchmarks (tests/CMakeLists.txt, bench/CMakeLists.txt).
#pragma once

#include <Eigen/Core>
#include <string>

#include <rrlab/collision/mesh_loader.hpp>

namespace rrlab {

// A capsule of `radius` around the z segment [0, length], every vertex on its
// surface: `around` vertices per ring, `rings` rings per hemisphere.
TriangleMesh capsule_mesh(double radius, double length, int around, int rings = 8);

// A box of full edge lengths `size`, centred on the origin: 8 vertices, 12 triangles.
TriangleMesh box_mesh(const Eigen::Vector3d& size);

// A UV sphere of `radius` around the origin, every vertex on the sphere:
// `around` meridians, `rings` latitude bands (poles included).
TriangleMesh sphere_mesh(double radius, int around, int rings);

// Writes the mesh as a Wavefront OBJ (for tests and generated fixtures).
void write_obj(const TriangleMesh& mesh, const std::string& path);

}  // namespace rrlab
