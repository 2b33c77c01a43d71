#include <rrlab/collision/mesh_loader.hpp>

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>

namespace rrlab {

void TriangleMesh::append(const TriangleMesh& other, const Eigen::Isometry3d& pose) {
  const int base = static_cast<int>(vertices.size());
  for (const Eigen::Vector3d& v : other.vertices) vertices.push_back(pose * v);
  for (const Eigen::Vector3i& t : other.triangles) triangles.push_back(t + Eigen::Vector3i::Constant(base));
}

namespace {

Eigen::Matrix4d to_matrix(const aiMatrix4x4& m) {
  Eigen::Matrix4d out;
  out << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3, m.d4;
  return out;
}

void collect(const aiScene& scene, const aiNode& node, const Eigen::Matrix4d& parent, TriangleMesh& out) {
  const Eigen::Matrix4d transform = parent * to_matrix(node.mTransformation);
  for (unsigned i = 0; i < node.mNumMeshes; ++i) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[i]];
    const int base = static_cast<int>(out.vertices.size());
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& p = mesh.mVertices[v];
      out.vertices.push_back((transform * Eigen::Vector4d(p.x, p.y, p.z, 1.0)).head<3>());
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines left by triangulation
      out.triangles.emplace_back(base + int(face.mIndices[0]), base + int(face.mIndices[1]), base + int(face.mIndices[2]));
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) collect(scene, *node.mChildren[c], transform, out);
}

}  // namespace

TriangleMesh load_mesh_file(const std::string& path, const Eigen::Vector3d& scale) {
  Assimp::Importer importer;
  // COLLADA files carry their unit and up axis; assimp applies both.
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices);
  if (!scene || !scene->mRootNode || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE))
    throw MeshError("cannot read mesh '" + path + "': " + importer.GetErrorString());
  TriangleMesh mesh;
  collect(*scene, *scene->mRootNode, Eigen::Matrix4d::Identity(), mesh);
  if (mesh.triangles.empty()) throw MeshError("mesh '" + path + "' has no triangles");
  if (int(mesh.triangles.size()) > kMaxMeshTriangles)
    throw MeshError("mesh '" + path + "' has " + std::to_string(mesh.triangles.size()) + " triangles, at most " +
                    std::to_string(kMaxMeshTriangles) + " allowed");
  for (Eigen::Vector3d& v : mesh.vertices) {
    v = v.cwiseProduct(scale);
    // NaN or 1e300 vertices would reach FCL's BVH fit (whose eigen solver gives up) and every distance
    if (!v.allFinite() || v.cwiseAbs().maxCoeff() > kMaxMeshCoordinate)
      throw MeshError("mesh '" + path + "' has a vertex at (" + std::to_string(v.x()) + ", " + std::to_string(v.y()) +
                      ", " + std::to_string(v.z()) + ") m after scaling: every coordinate must be finite and within " +
                      std::to_string(int(kMaxMeshCoordinate)) + " m");
  }
  return mesh;
}

}  // namespace rrlab
