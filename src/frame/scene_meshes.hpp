// The scene's meshes on the GPU, and the one loop that draws them: a resource of the frame,
// shared by every technique that draws scene meshes with a fragment stage of its own over the
// common vertex stage frame/mesh.vert (world position and normal out): the mesh kind's
// geometry pass, the cutters' passes (region-of-interest seeding, ghost geometry, depth
// sprites) and the shadow map.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "cutaway/geometry/grid_lod.hpp"
#include "cutaway/gl/objects.hpp"
#include "cutaway/scene/scene.hpp"

namespace cutaway {

// Uniform locations of src/frame/mesh.vert, used by every program drawing scene meshes.
namespace meshUniform {
constexpr GLint kModel = 0, kNormalMatrix = 4;
}

// One triangle mesh on the GPU: interleaved positions and normals (attributes 0 and 1 of
// frame/mesh.vert) and indices. A grid mesh (Mesh::grid) is drawn with a level of detail: its
// buffers hold the chunks' levels the last view selected (the coarsest until then); the grid
// mesh must outlive it. A mesh with coarser versions holds the one the last view selected.
class GpuMesh {
 public:
  GpuMesh() = default;
  // Throws cutaway::Error beyond `maxTriangles` or when the device has no memory for it.
  static constexpr std::size_t kMaxTriangles = std::size_t(1) << 29;
  explicit GpuMesh(const cutaway::Mesh& mesh, std::size_t maxTriangles = kMaxTriangles);
  // With coarser versions of the mesh (SceneObject::coarser); the mesh must outlive this.
  GpuMesh(const cutaway::Mesh& mesh, const std::vector<SceneObject::Coarser>& coarser);
  void draw() const;
  // The detail for `view`: a grid mesh's chunk levels (GridLod::select), else the coarsest
  // version whose error projects to at most view.pixelError pixels at the mesh's nearest
  // point. The buffers are rebuilt only when the choice changes.
  void selectDetail(const GridLod::View& view);
  std::size_t triangles() const { return std::size_t(indexCount_) / 3; }
  // Object space, of every version (a grid's levels keep a subset of its nodes).
  const Bounds& bounds() const { return bounds_; }
  // Whether selectDetail can change what is drawn (a grid, or coarser versions).
  bool hasDetail() const { return lod_ || !coarser_.empty(); }

 private:
  void upload(const cutaway::Mesh& mesh, const std::vector<glm::uvec3>& triangles, bool compact);

  const cutaway::Mesh* source_ = nullptr;  // read again by selectDetail (grids, versions)
  gl::VertexArray vertexArray_;
  gl::Buffer vertices_, indices_;
  GLsizei indexCount_ = 0;
  std::optional<GridLod> lod_;
  std::vector<std::uint8_t> levels_;
  std::vector<SceneObject::Coarser> coarser_;
  Bounds bounds_;            // of the mesh and its coarser versions, object space
  std::size_t version_ = 0;  // 0 the mesh, k coarser_[k − 1]
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
  // Calls `perObject` for every object for which `which` is true, in the same order, with a
  // function that draws the object with a program: sets the program's meshUniform transforms,
  // binds it and draws (as often as `perObject` asks, with its uniforms and state each time).
  using DrawWith = std::function<void(GLuint program)>;
  void forEach(
      const Filter& which,
      const std::function<void(const SceneObject&, std::size_t, const DrawWith&)>& perObject) const;
  const Scene& scene() const { return scene_; }
  const GpuMesh& mesh(std::size_t object) const { return meshes_[object]; }
  float time() const { return time_; }
  std::size_t triangles() const;  // of every mesh, grid meshes at their selected detail
  // The detail of the grid meshes and of the meshes with coarser versions for a view of
  // `viewportHeight` pixels whose screen-space error may reach `pixelError`
  // (Scene::pixelError), each at its object's transform.
  void selectDetail(const glm::mat4& viewProjection, const glm::mat4& projection,
                    const glm::vec3& eye, float viewportHeight, float pixelError);
  // The animation time at which objects are drawn (SceneObject::transformAt).
  void setTime(float time) { time_ = time; }

 private:
  const Scene& scene_;
  std::vector<GpuMesh> meshes_;
  float time_ = 0.0f;
};

}  // namespace cutaway
