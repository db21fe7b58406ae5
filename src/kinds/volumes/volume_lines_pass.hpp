// Line drawings of scene volumes (Burns11 §2.4) in the frame, after the volumes pass. Each frame
// the lines of every volume with "lines" are extracted on the CPU (styles/volume_lines: one
// tracker per isovalue and family, walking from the previous frame's cells), then:
//   volumeLineSurfaces  per pixel, the view depth of the nearest crossing of a drawn isovalue
//                       among the samples the cutters keep, or of the opaque surfaces (AOV
//                       volumeLineSurfaceDepth): what hides a line
//   volumeLines         each segment decided at its middle by the cutters that cut the volume
//                       and tested against that depth (a texel per segment), then the halos and
//                       the lines over the final colour (AOV volumeLineCoverage)
// A volume whose lines are "only" is not ray cast (VolumeKind skips it).
#pragma once

#include <functional>
#include <map>
#include <utility>
#include <vector>

#include "cutaway/gl/objects.hpp"
#include "cutaway/styles/volume_lines.hpp"
#include "cutters/cutter.hpp"
#include "frame/frame_setup.hpp"
#include "frame/frame_uniforms.hpp"
#include "frame/fullscreen.hpp"

namespace cutaway {

class VolumeLinesPass {
 public:
  // `bindVolume(program, i)`: binds volume i's textures and shared uniforms (VolumeKind's).
  VolumeLinesPass(FrameSetup& setup, std::function<void(GLuint, std::size_t)> bindVolume);
  static bool present(const Scene& scene);
  void prepare(const std::vector<ActiveCutter>& cutters);
  void addPasses(Frame& frame);
  void beginFrame(const FrameState& state);
  // The last frame's lines, each run of segments split by the fates the frame drew them with.
  VolumeLineDrawing drawing() const;

 private:
  struct Family {
    std::size_t iso = 0, plane = 0;
    VolumeLineQuery query;
    VolumeLineTracker tracker;
  };
  struct Lines {
    std::size_t volume = 0;
    VolumeLineStyle style;  // what the families were made for
    std::vector<Family> families;
    gl::Texture blocks;  // the value range per block (volume_blocks.hpp), RG32F
  };
  struct Segment {  // the vertex layout: two per segment
    glm::vec3 position;
    glm::vec4 pen;  // colour, width in pixels
    float importance;
  };
  struct Run {  // one polyline's segments
    std::size_t volume, first, count;
    VolumeLineKind kind;
    glm::vec4 pen;
  };
  void extract(const Camera& camera);
  void drawSurfaces() const;
  void decideSegments(const PassContext& pass) const;
  void drawLines(const PassContext& pass) const;
  void setCommonUniforms(GLuint program, std::size_t volume) const;
  // The first segment and the count of a volume's lines.
  std::pair<std::size_t, std::size_t> segmentRange(std::size_t volume) const;
  GLuint surfaceProgram(const SceneVolume& v) const;
  // The pen and importance of a line of family f of `lines`.
  glm::vec4 pen(const Lines& lines, const Family& f, VolumeLineKind kind) const;
  float importance(const Lines& lines, const Family& f) const;

  FrameSetup& setup_;
  std::function<void(GLuint, std::size_t)> bindVolume_;
  const std::vector<ActiveCutter>* cutters_ = nullptr;
  std::vector<Lines> lines_;
  mutable std::map<int, gl::Program> surfacePrograms_;
  gl::Program lineProgram_, fateProgram_;
  gl::VertexArray vertexArray_, middleArray_;
  gl::Buffer vertices_, middles_;
  std::size_t vertexCapacity_ = 0;
  std::vector<Segment> segments_;  // this frame's, two vertices per segment
  std::vector<Run> runs_;
  FullscreenTriangle fullscreen_;
  Target surfaces_, coverage_, depth_;
  // The last frame's fate of each segment (volume_line_segment_fate.frag), a texel each.
  mutable gl::Texture fates_;
  mutable gl::Framebuffer fateFramebuffer_;
  mutable int fateRows_ = 0;
  glm::mat4 viewProjection_{1.0f}, view_{1.0f};
};

}  // namespace cutaway
