#include "frame/scene_meshes.hpp"

#include <string>

#include "cutaway/core/error.hpp"

namespace cutaway {

GpuMesh::GpuMesh(const cutaway::Mesh& mesh, std::size_t maxTriangles) {
  // glDrawElements counts indices in a GLsizei.
  if (mesh.triangles.size() > maxTriangles)
    throw Error(std::to_string(mesh.triangles.size()) + " triangles exceed the limit of " +
                std::to_string(maxTriangles) + " per mesh");
  std::vector<float> interleaved;
  interleaved.reserve(mesh.positions.size() * 6);
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const auto& p = mesh.positions[i];
    const auto& n = mesh.normals[i];
    interleaved.insert(interleaved.end(), {p.x, p.y, p.z, n.x, n.y, n.z});
  }
  if (gl::outOfMemory([&] {
        vertices_ =
            gl::Buffer::create(GLsizeiptr(interleaved.size() * sizeof(float)), interleaved.data());
        indices_ = gl::Buffer::create(GLsizeiptr(mesh.triangles.size() * sizeof(glm::uvec3)),
                                      mesh.triangles.data());
      }))
    throw Error("the device is out of memory for its " + std::to_string(mesh.triangles.size()) +
                " triangles");
  indexCount_ = GLsizei(mesh.triangles.size() * 3);
  vertexArray_ = gl::VertexArray::create();
  const GLuint vao = vertexArray_.id();
  glVertexArrayVertexBuffer(vao, 0, vertices_.id(), 0, 6 * sizeof(float));
  glVertexArrayElementBuffer(vao, indices_.id());
  for (GLuint attribute : {0u, 1u}) {
    glEnableVertexArrayAttrib(vao, attribute);
    glVertexArrayAttribFormat(vao, attribute, 3, GL_FLOAT, GL_FALSE, attribute * 3 * sizeof(float));
    glVertexArrayAttribBinding(vao, attribute, 0);
  }
}

void GpuMesh::draw() const {
  glBindVertexArray(vertexArray_.id());
  glDrawElements(GL_TRIANGLES, indexCount_, GL_UNSIGNED_INT, nullptr);
}

SceneMeshes::SceneMeshes(const Scene& scene) : scene_(scene) {
  for (const auto& object : scene.objects) {
    try {
      meshes_.emplace_back(*object.mesh);
    } catch (const Error& e) {
      throw Error(object.name, "", e.reason());
    }
  }
}

void SceneMeshes::draw(GLuint program, const Filter& which,
                    const std::function<void(const SceneObject&, std::size_t)>& perObject) const {
  glUseProgram(program);
  for (std::size_t i = 0; i < scene_.objects.size(); ++i) {
    const SceneObject& o = scene_.objects[i];
    if (!which(o, i)) continue;
    const glm::mat4 model = o.transformAt(time_);
    const glm::mat4 normalMatrix = glm::transpose(glm::inverse(model));
    glProgramUniformMatrix4fv(program, meshUniform::kModel, 1, GL_FALSE, &model[0][0]);
    glProgramUniformMatrix4fv(program, meshUniform::kNormalMatrix, 1, GL_FALSE,
                              &normalMatrix[0][0]);
    perObject(o, i);
    meshes_[i].draw();
  }
}

}  // namespace cutaway
