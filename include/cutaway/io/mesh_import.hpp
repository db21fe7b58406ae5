// cutaway/io/mesh_import.hpp — triangle meshes from any format Assimp reads (OBJ, PLY, STL,
// glTF/GLB, IFC, DAE, FBX…), gzip-compressed files included ("room.stl.gz").
//
// A file is returned as its mesh nodes: each node's meshes merged, with the node's
// accumulated transform baked in. Every mesh has normals (computed where the file had none),
// no degenerate triangles, and a topology report (watertightness).
//
//   for (const auto& node : cutaway::importMeshNodes("engine.glb"))
//     std::printf("%s: %zu triangles\n", node.name.c_str(), node.mesh.triangles.size());
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "cutaway/geometry/mesh.hpp"

namespace cutaway {

struct ImportedNode {
  // The node's name, made unique within the file. A node the file leaves unnamed, which
  // Assimp calls by its place (glTF: "nodes[74]"), takes its mesh's name, else its parent's,
  // else its material's; `id` keeps the place, which patterns match too ("" when named).
  std::string name;
  std::string id;
  Mesh mesh;                       // in file space
  std::optional<glm::vec3> color;  // diffuse / base colour of its first material
};

// Throws cutaway::Error naming the file and the reason. The importer runs in a child process
// under importLimits() (cutaway/core/contained.hpp): a file that crashes Assimp, hangs it or
// makes it allocate without bound is an Error too.
std::vector<ImportedNode> importMeshNodes(const std::filesystem::path& file);

}  // namespace cutaway
