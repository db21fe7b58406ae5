// The scene's meshes on the GPU, and the one loop that draws them: a resource of the frame,
// shared by every technique that draws scene meshes with a fragment stage of its own over the
// common vertex stage frame/mesh.vert (world position and normal out): the mesh kind's
// geometry pass, the cutters' passes (region-of-interest seeding, ghost geometry, depth
// sprites) and the shadow map.
#pragma once

#include <functional>
#include <vector>

#include "cutaway/gl/objects.hpp"
#include "cutaway/scene/scene.hpp"

namespace cutaway {

// Uniform locations of src/frame/mesh.vert, used by every program drawing scene meshes.
namespace meshUniform {
constexpr GLint kModel = 0, kNormalMatrix = 4;
}

// One triangle mesh on the GPU: interleaved positions and normals (attributes 0 and 1 of
// frame/mesh.vert) and indices.
class GpuMesh {
 public:
  GpuMesh() = default;
  // Throws cutaway::Error beyond `maxTriangles` or when the device has no memory for it.
  static constexpr std::size_t kMaxTriangles = std::size_t(1) << 29;
  explicit GpuMesh(const cutaway::Mesh& mesh, std::size_t maxTriangles = kMaxTriangles);
  void draw() const;

 private:
  gl::VertexArray vertexArray_;
  gl::Buffer vertices_, indices_;
  GLsizei indexCount_ = 0;
};

class SceneMeshes {
 public:
  explicit SceneMeshes(const Scene& scene);
  // Draws, with `program`, every object for which `which` is true: sets the transforms of
  // meshUniform, then calls `perObject` (index in scene.objects) for the program's own
  // uniforms. Proxies have meshes too (cutters seed from them).
  using Filter = std::function<bool(const SceneObject&, std::size_t)>;
  void draw(GLuint program, const Filter& which,
            const std::function<void(const SceneObject&, std::size_t)>& perObject) const;
  const Scene& scene() const { return scene_; }
  const GpuMesh& mesh(std::size_t object) const { return meshes_[object]; }
  float time() const { return time_; }
  // The animation time at which objects are drawn (SceneObject::transformAt).
  void setTime(float time) { time_ = time; }

 private:
  const Scene& scene_;
  std::vector<GpuMesh> meshes_;
  float time_ = 0.0f;
};

}  // namespace cutaway
