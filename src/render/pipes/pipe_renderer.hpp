// Konev18 §§5–7 on the GPU: the scene's pipe networks as camera-facing billboards built in a
// geometry shader from the node buffer, cut open by static proxy geometry that marks the
// stencil buffer in two passes, with the water in cut pipes and shafts. The frame's passes:
//   pipeOwners  the proxies' nearest pipe id per pixel (the §9 interference fix)
//   pipes       stencil cleared; proxy pass 1 (cut surface, stencil 2), pass 2 (inside,
//               stencil 1), Fig. 10's back-face reset (stencil 0); billboards outside
//               (stencil 0), inside (1) and over cut surfaces (2); shaft water
//   pipeAovs    the stencil after the proxy passes and the pipe class, as AOVs
#pragma once

#include <map>
#include <string>
#include <vector>

#include "cutaway/gl/objects.hpp"
#include "cutaway/render/frame.hpp"
#include "cutaway/scene/scene.hpp"
#include "render/fullscreen.hpp"

namespace cutaway {

class PipeRenderer {
 public:
  // `defines`: the geometry pass's cutter defines (for the G-buffer layout); `style`: the
  // style's GLSL file; `gbuffer`: the geometry pass's colour targets, in order.
  PipeRenderer(const Scene& scene, Frame& frame, std::map<std::string, std::string> defines,
               const std::string& style, const std::vector<std::string>& gbuffer);
  // Whether any network is drawn as billboards (else the renderer adds no passes).
  bool active() const { return !networks_.empty(); }
  // The billboards into the bound shadow-map target, with the light's frame uniforms bound
  // (src/styles/shadows): each quad faces the light. Only with the scene's shadows on (the
  // program is built for them).
  void drawShadowCasters() const;

 private:
  struct NetworkGpu {
    std::size_t network;
    int objectId;
    gl::Buffer pipes;  // PipeRecord per pipe (src/render/pipes/pipes.glsl)
    gl::VertexArray nodeArray, proxyArray, waterArray;
    gl::Buffer nodes, nodeIndices, proxy, water;
    GLsizei nodeIndexCount = 0, proxyVertexCount = 0, waterCount = 0;
  };
  void setNetworkUniforms(GLuint program, const NetworkGpu& n) const;
  void drawOwners();
  void drawPipes();
  void drawAovs();

  const Scene& scene_;
  Frame& frame_;
  std::vector<NetworkGpu> networks_;
  gl::Program billboardProgram_, shadowProgram_, proxyProgram_, ownerProgram_, waterProgram_,
      aovProgram_;
  gl::Texture stencilView_;
  FullscreenTriangle fullscreen_;
  GLuint gbufferTargets_ = 0;
};

}  // namespace cutaway
