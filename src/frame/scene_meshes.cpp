#include "frame/scene_meshes.hpp"

#include <algorithm>
#include <string>

#include "cutaway/core/error.hpp"

namespace cutaway {

namespace {

// The mesh's triangles as an index list: its own, or a grid's implied ones written out into
// `written`.
const std::vector<glm::uvec3>& indexList(const cutaway::Mesh& mesh,
                                         std::vector<glm::uvec3>& written) {
  if (!mesh.impliedTriangles()) return mesh.triangles;
  written.resize(mesh.triangleCount());
  for (std::size_t i = 0; i < written.size(); ++i) written[i] = mesh.triangle(i);
  return written;
}

}  // namespace

GpuMesh::GpuMesh(const cutaway::Mesh& mesh, std::size_t maxTriangles)
    : source_(&mesh), lod_(GridLod::build(mesh)), bounds_(mesh.bounds()) {
  // glDrawElements counts indices in a GLsizei.
  if (mesh.triangleCount() > maxTriangles)
    throw Error(std::to_string(mesh.triangleCount()) + " triangles exceed the limit of " +
                std::to_string(maxTriangles) + " per mesh");
  vertexArray_ = gl::VertexArray::create();
  const GLuint vao = vertexArray_.id();
  for (GLuint attribute : {0u, 1u}) {
    glEnableVertexArrayAttrib(vao, attribute);
    glVertexArrayAttribFormat(vao, attribute, 3, GL_FLOAT, GL_FALSE, attribute * 3 * sizeof(float));
    glVertexArrayAttribBinding(vao, attribute, 0);
  }
  if (lod_) {
    levels_.assign(std::size_t(lod_->chunkCount()), GridLod::kLevels - 1);
    upload(mesh, lod_->triangles(levels_), true);
  } else {
    std::vector<glm::uvec3> written;
    upload(mesh, indexList(mesh, written), false);
  }
}

GpuMesh::GpuMesh(const cutaway::Mesh& mesh, const std::vector<SceneObject::Coarser>& coarser)
    : GpuMesh(mesh) {
  coarser_ = coarser;
  for (const SceneObject::Coarser& c : coarser_) bounds_.extend(c.mesh->bounds());
}

// A grid mesh's buffers hold only the nodes its drawn triangles use, renumbered, so that the
// device's memory follows the detail drawn, not the terrain's size.
void GpuMesh::upload(const cutaway::Mesh& mesh, const std::vector<glm::uvec3>& triangles,
                     bool compact) {
  std::vector<std::uint32_t> nodes;  // the vertex buffer's nodes, in order
  std::vector<glm::uvec3> renumbered;
  if (compact) {
    std::vector<std::uint32_t> slot(mesh.positions.size(), ~0u);
    renumbered = triangles;
    for (glm::uvec3& t : renumbered)
      for (int k = 0; k < 3; ++k) {
        if (slot[t[k]] == ~0u) slot[t[k]] = std::uint32_t(nodes.size()), nodes.push_back(t[k]);
        t[k] = slot[t[k]];
      }
  }
  const std::vector<glm::uvec3>& indices = compact ? renumbered : triangles;
  const std::size_t count = compact ? nodes.size() : mesh.positions.size();
  constexpr std::size_t kStride = 6 * sizeof(float);
  if (gl::outOfMemory([&] {
        vertices_ = gl::Buffer::create(GLsizeiptr(std::max<std::size_t>(count, 1) * kStride),
                                       nullptr, GL_DYNAMIC_STORAGE_BIT);
        indices_ =
            gl::Buffer::create(GLsizeiptr(indices.size() * sizeof(glm::uvec3)), indices.data());
      }))
    throw Error("the device is out of memory for its " + std::to_string(indices.size()) +
                " triangles");
  // Interleaved a block at a time: a copy of a large mesh's vertices would double them.
  constexpr std::size_t kBlock = std::size_t(1) << 16;
  std::vector<float> interleaved;
  for (std::size_t begin = 0; begin < count; begin += kBlock) {
    interleaved.clear();
    for (std::size_t i = begin; i < std::min(count, begin + kBlock); ++i) {
      const std::size_t node = compact ? nodes[i] : i;
      const glm::vec3& p = mesh.positions[node];
      const glm::vec3& n = mesh.normals[node];
      interleaved.insert(interleaved.end(), {p.x, p.y, p.z, n.x, n.y, n.z});
    }
    glNamedBufferSubData(vertices_.id(), GLintptr(begin * kStride),
                         GLsizeiptr(interleaved.size() * sizeof(float)), interleaved.data());
  }
  indexCount_ = GLsizei(indices.size() * 3);
  glVertexArrayVertexBuffer(vertexArray_.id(), 0, vertices_.id(), 0, kStride);
  glVertexArrayElementBuffer(vertexArray_.id(), indices_.id());
}

void GpuMesh::selectDetail(const GridLod::View& view) {
  if (!coarser_.empty()) {
    // The coarsest version within the pixel error where the mesh comes nearest.
    const float pixels = GridLod::pixelsPerUnit(view, bounds_);
    std::size_t version = 0;
    while (version < coarser_.size() && (view.pixelError > 0.0f || pixels == 0.0f) &&
           coarser_[version].error * pixels <= view.pixelError)
      ++version;
    if (version == version_) return;
    version_ = version;
    const cutaway::Mesh& mesh = version == 0 ? *source_ : *coarser_[version - 1].mesh;
    std::vector<glm::uvec3> written;
    upload(mesh, indexList(mesh, written), false);
    return;
  }
  if (!lod_) return;
  std::vector<std::uint8_t> levels = lod_->select(view);
  if (levels == levels_) return;
  levels_ = std::move(levels);
  // Full detail everywhere is the mesh itself (pixelError 0): no renumbering.
  if (std::all_of(levels_.begin(), levels_.end(), [](std::uint8_t l) { return l == 0; })) {
    std::vector<glm::uvec3> written;
    upload(*source_, indexList(*source_, written), false);
  } else {
    upload(*source_, lod_->triangles(levels_), true);
  }
}

void GpuMesh::draw() const {
  glBindVertexArray(vertexArray_.id());
  glDrawElements(GL_TRIANGLES, indexCount_, GL_UNSIGNED_INT, nullptr);
}

SceneMeshes::SceneMeshes(const Scene& scene) : scene_(scene) {
  for (const auto& object : scene.objects) {
    try {
      meshes_.emplace_back(*object.mesh, object.coarser);
    } catch (const Error& e) {
      throw Error(object.name, "", e.reason());
    }
  }
}

void SceneMeshes::selectDetail(const glm::mat4& viewProjection, const glm::mat4& projection,
                               const glm::vec3& eye, float viewportHeight, float pixelError) {
  for (std::size_t i = 0; i < scene_.objects.size(); ++i)
    if (meshes_[i].hasDetail())
      meshes_[i].selectDetail({.model = scene_.objects[i].transformAt(time_),
                               .viewProjection = viewProjection,
                               .projection = projection,
                               .eye = eye,
                               .viewportHeight = viewportHeight,
                               .pixelError = pixelError});
}

std::size_t SceneMeshes::triangles() const {
  std::size_t n = 0;
  for (const GpuMesh& m : meshes_) n += m.triangles();
  return n;
}

void SceneMeshes::draw(
    GLuint program, const Filter& which,
    const std::function<void(const SceneObject&, std::size_t)>& perObject) const {
  forEach(which, [&](const SceneObject& o, std::size_t i, const DrawWith& drawWith) {
    perObject(o, i);
    drawWith(program);
  });
}

void SceneMeshes::forEach(
    const Filter& which,
    const std::function<void(const SceneObject&, std::size_t, const DrawWith&)>& perObject) const {
  GLuint used = 0;
  for (std::size_t i = 0; i < scene_.objects.size(); ++i) {
    const SceneObject& o = scene_.objects[i];
    if (!which(o, i)) continue;
    const glm::mat4 model = o.transformAt(time_);
    glm::mat4 normalMatrix = glm::transpose(glm::inverse(model));
    // Only its directions count. Under a scale far from 1 the normals came out too short for
    // mesh.frag's vanishing-normal test (1e12), or zero where the 4×4 determinant overflowed
    // (1e14): a black object. Such a matrix is worked out in double and scaled to a largest
    // entry of 1; every other is left as it was.
    const auto largest = [](const auto& m) {
      double l = 0.0;
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) l = std::max(l, double(std::abs(m[c][r])));
      return l;
    };
    if (const double l = largest(normalMatrix); !(l >= 1e-3 && l <= 1e3)) {
      const glm::dmat3 n = glm::transpose(glm::inverse(glm::dmat3(glm::mat3(model))));
      normalMatrix = glm::mat4(glm::mat3(n / largest(n)));
    }
    // A mirroring transform turns the triangles' winding on screen: its outside must still
    // be the front (gl_FrontFacing, face culling).
    glFrontFace(glm::determinant(glm::mat3(model)) < 0.0f ? GL_CW : GL_CCW);
    perObject(o, i, [&](GLuint program) {
      if (program != used) glUseProgram(used = program);
      glProgramUniformMatrix4fv(program, meshUniform::kModel, 1, GL_FALSE, &model[0][0]);
      glProgramUniformMatrix4fv(program, meshUniform::kNormalMatrix, 1, GL_FALSE,
                                &normalMatrix[0][0]);
      meshes_[i].draw();
    });
  }
  glFrontFace(GL_CCW);
}

}  // namespace cutaway
