// Konev18 §§5–7 on the GPU: the scene's pipe networks as camera-facing billboards built in a
// geometry shader from the node buffer, cut open by static proxy geometry that marks the
// stencil buffer in three passes, with the water in cut pipes and shafts. The frame's passes:
//   pipeOwners  the proxies' nearest pipe id per pixel (the §9 interference fix)
//   pipeProxies stencil cleared; proxy pass 1 (cut surface, stencil 2), pass 2 (inside,
//               stencil 1), Fig. 10's back-face reset (stencil 4)
//   pipeStencilMasks  each pixel's samples at stencil 0, 2 and 1, as bit masks
//   pipes       billboards: the outside over stencil 0, 2 and 4 (the samples each leaves out
//               taken from the masks), the inside over 1; shaft water
//   pipeAovs    the stencil after the proxy passes and the pipe class, as AOVs
#pragma once

#include <string>
#include <vector>

#include "cutaway/gl/objects.hpp"
#include "frame/fullscreen.hpp"
#include "kinds/kind.hpp"

namespace cutaway {

class PipeKind : public GeometryKind {
 public:
  // Uploads the networks drawn as billboards.
  explicit PipeKind(FrameSetup& setup);
  // Whether any network is drawn as billboards (else the composer leaves the kind out).
  static bool present(const Scene& scene);
  bool needsStencil(const std::vector<ActiveCutter>&) const override { return true; }
  // Builds the programs and declares the owner, class and stencil targets.
  void prepare(const std::vector<ActiveCutter>& cutters) override;
  void addPassesAfterGeometry(Frame& frame) override;
  // The billboards into the bound shadow-map target, with the light's frame uniforms bound
  // (src/styles/shadows): each quad faces the light. Only with the scene's shadows on (the
  // program is built for them).
  void drawShadowCasters() const override;
  // Every network is of interest, as the shafts it contributes are: the tubes' rear hulls
  // seed a cutaway surface around them (billboard_rear_hull.frag).
  void drawInterestRearHulls(const RearHullRequest& request) const override;

 private:
  struct NetworkGpu {
    std::size_t network;
    int objectId;
    gl::Buffer pipes;  // PipeRecord per pipe (src/kinds/pipes/pipes.glsl)
    gl::VertexArray nodeArray, proxyArray, waterArray;
    gl::Buffer nodes, nodeIndices, proxy, endTriangles, water;
    // endTriangles: the proxies' end-triangle vertices (Fig. 10's pass draws only those).
    GLsizei nodeIndexCount = 0, proxyVertexCount = 0, endTriangleIndexCount = 0, waterCount = 0;
  };
  void setNetworkUniforms(GLuint program, const NetworkGpu& n) const;
  // Every network's billboards with `program`, only the radii set (shadow casters, rear hulls).
  void drawTubes(GLuint program) const;
  void drawOwners();
  void drawProxies();
  void drawPipes();
  void drawAovs();

  FrameSetup& setup_;
  const Scene& scene_;
  std::vector<NetworkGpu> networks_;
  gl::Program outsideProgram_, insideProgram_, shadowProgram_, rearHullProgram_, proxyProgram_,
      ownerProgram_, waterProgram_, aovProgram_, stencilMasksProgram_;
  gl::Texture stencilView_;
  FullscreenTriangle fullscreen_;
  GLuint gbufferTargets_ = 0;
  bool cutOpen_ = false;  // some network has proxies (a cut stretch): the stencil is not all 0
  GLuint pipesBlock_, ownerUnit_, ownerDepthUnit_, stencilMasksUnit_;
  Target owner_, ownerDepth_, stencilMasks_, pipeClass_, stencilAov_, classAov_;
};

}  // namespace cutaway
