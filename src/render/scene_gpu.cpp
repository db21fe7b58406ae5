#include "render/scene_gpu.hpp"

namespace cutaway {

SceneGpu::SceneGpu(const Scene& scene) : scene_(scene) {
  for (const auto& object : scene.objects) {
    const cutaway::Mesh& mesh = *object.mesh;
    std::vector<float> interleaved;
    interleaved.reserve(mesh.positions.size() * 6);
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      const auto& p = mesh.positions[i];
      const auto& n = mesh.normals[i];
      interleaved.insert(interleaved.end(), {p.x, p.y, p.z, n.x, n.y, n.z});
    }
    Mesh g;
    g.vertices =
        gl::Buffer::create(GLsizeiptr(interleaved.size() * sizeof(float)), interleaved.data());
    g.indices = gl::Buffer::create(GLsizeiptr(mesh.triangles.size() * sizeof(glm::uvec3)),
                                   mesh.triangles.data());
    g.indexCount = GLsizei(mesh.triangles.size() * 3);
    g.vertexArray = gl::VertexArray::create();
    const GLuint vao = g.vertexArray.id();
    glVertexArrayVertexBuffer(vao, 0, g.vertices.id(), 0, 6 * sizeof(float));
    glVertexArrayElementBuffer(vao, g.indices.id());
    for (GLuint attribute : {0u, 1u}) {
      glEnableVertexArrayAttrib(vao, attribute);
      glVertexArrayAttribFormat(vao, attribute, 3, GL_FLOAT, GL_FALSE,
                                attribute * 3 * sizeof(float));
      glVertexArrayAttribBinding(vao, attribute, 0);
    }
    meshes_.push_back(std::move(g));
  }
}

void SceneGpu::draw(GLuint program, const std::function<bool(const SceneObject&)>& which,
                    const std::function<void(const SceneObject&, std::size_t)>& perObject) const {
  glUseProgram(program);
  for (std::size_t i = 0; i < scene_.objects.size(); ++i) {
    const SceneObject& o = scene_.objects[i];
    if (!which(o)) continue;
    const glm::mat4 model = o.transformAt(time_);
    const glm::mat4 normalMatrix = glm::transpose(glm::inverse(model));
    glProgramUniformMatrix4fv(program, meshUniform::kModel, 1, GL_FALSE, &model[0][0]);
    glProgramUniformMatrix4fv(program, meshUniform::kNormalMatrix, 1, GL_FALSE,
                              &normalMatrix[0][0]);
    perObject(o, i);
    glBindVertexArray(meshes_[i].vertexArray.id());
    glDrawElements(GL_TRIANGLES, meshes_[i].indexCount, GL_UNSIGNED_INT, nullptr);
  }
}

}  // namespace cutaway
