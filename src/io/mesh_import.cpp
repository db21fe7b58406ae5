#include "cutaway/io/mesh_import.hpp"

#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <zlib.h>

#include <assimp/Importer.hpp>
#include <cmath>
#include <map>

#include "cutaway/core/error.hpp"

namespace cutaway {

namespace {

std::vector<char> readGzip(const std::filesystem::path& file) {
  gzFile gz = gzopen(file.c_str(), "rb");
  if (!gz) throw Error(file.string(), "", "cannot open");
  std::vector<char> data;
  char chunk[1 << 16];
  int n = 0;
  while ((n = gzread(gz, chunk, sizeof chunk)) > 0) data.insert(data.end(), chunk, chunk + n);
  int errnum = 0;
  const std::string message = n < 0 ? gzerror(gz, &errnum) : "";
  gzclose(gz);
  if (n < 0) throw Error(file.string(), "", "gzip decompression failed: " + message);
  return data;
}

glm::mat4 toGlm(const aiMatrix4x4& m) {
  // Assimp matrices are row-major; glm is column-major.
  return glm::transpose(glm::mat4(m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3,
                                  m.c4, m.d1, m.d2, m.d3, m.d4));
}

// One aiMesh as a cutaway Mesh: triangles only (points and lines were sorted out), normals
// recomputed when missing or invalid.
Mesh convert(const aiMesh& in, bool& normalsComputed) {
  Mesh m;
  m.positions.reserve(in.mNumVertices);
  for (unsigned i = 0; i < in.mNumVertices; ++i)
    m.positions.emplace_back(in.mVertices[i].x, in.mVertices[i].y, in.mVertices[i].z);
  for (unsigned f = 0; f < in.mNumFaces; ++f) {
    const aiFace& face = in.mFaces[f];
    if (face.mNumIndices == 3)
      m.triangles.emplace_back(face.mIndices[0], face.mIndices[1], face.mIndices[2]);
  }
  bool valid = in.HasNormals();
  if (valid) {
    m.normals.reserve(in.mNumVertices);
    for (unsigned i = 0; i < in.mNumVertices && valid; ++i) {
      const glm::vec3 n(in.mNormals[i].x, in.mNormals[i].y, in.mNormals[i].z);
      const float len = glm::length(n);
      valid = std::isfinite(len) && len > 1e-6f;
      m.normals.push_back(valid ? n / len : n);
    }
  }
  if (!valid) {
    computeVertexNormals(m);
    normalsComputed = true;
  }
  return m;
}

}  // namespace

std::vector<ImportedNode> importMeshNodes(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw Error(file.string(), "", "mesh file not found");
  Assimp::Importer importer;
  // Points and lines carry no surface: drop them rather than fail.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                              aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const unsigned flags =
      aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_JoinIdenticalVertices;
  const aiScene* scene = nullptr;
  if (file.extension() == ".gz") {
    const std::vector<char> data = readGzip(file);
    const std::string hint = file.stem().extension().string();  // "room.stl.gz" → ".stl"
    scene = importer.ReadFileFromMemory(data.data(), data.size(), flags,
                                        hint.empty() ? "" : hint.c_str() + 1);
  } else {
    scene = importer.ReadFile(file.string(), flags);
  }
  if (!scene || !scene->mRootNode)
    throw Error(file.string(), "", std::string("cannot import mesh: ") + importer.GetErrorString());

  std::vector<ImportedNode> nodes;
  std::map<std::string, int> nameCount;
  auto visit = [&](auto&& self, const aiNode* node, const glm::mat4& parent) -> void {
    const glm::mat4 transform = parent * toGlm(node->mTransformation);
    if (node->mNumMeshes > 0) {
      ImportedNode out;
      std::string name = node->mName.length ? node->mName.C_Str() : "node";
      const int seen = nameCount[name]++;
      out.name = seen ? name + "#" + std::to_string(seen + 1) : name;
      bool normalsComputed = false;
      for (unsigned i = 0; i < node->mNumMeshes; ++i) {
        const aiMesh* mesh = scene->mMeshes[node->mMeshes[i]];
        if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
        out.mesh.append(convert(*mesh, normalsComputed), transform);
        if (!out.color && mesh->mMaterialIndex < scene->mNumMaterials) {
          aiColor4D c;
          const aiMaterial* material = scene->mMaterials[mesh->mMaterialIndex];
          // Assimp invents "DefaultMaterial" for files without materials: not the file's colour.
          if (material->GetName() == aiString(AI_DEFAULT_MATERIAL_NAME)) continue;
          if (material->Get(AI_MATKEY_BASE_COLOR, c) == AI_SUCCESS ||
              material->Get(AI_MATKEY_COLOR_DIFFUSE, c) == AI_SUCCESS)
            out.color = glm::clamp(glm::vec3(c.r, c.g, c.b), 0.0f, 1.0f);
        }
      }
      out.mesh.report.normalsComputed = normalsComputed;
      out.mesh.report.droppedDegenerate = dropDegenerateTriangles(out.mesh);
      if (!out.mesh.triangles.empty()) {
        analyzeTopology(out.mesh);
        nodes.push_back(std::move(out));
      }
    }
    for (unsigned i = 0; i < node->mNumChildren; ++i) self(self, node->mChildren[i], transform);
  };
  visit(visit, scene->mRootNode, glm::mat4(1.0f));
  if (nodes.empty()) throw Error(file.string(), "", "the file contains no triangles");
  return nodes;
}

}  // namespace cutaway
