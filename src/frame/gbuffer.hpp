// The scene's multisampled G-buffer and its resolve. Every program that draws visible surfaces
// writes it through frame/gbuffer.glsl (colour, normal + line weight, object id + view depth,
// cut mask, then the channels techniques add); the "composite" pass
// averages the samples into the final colour and blends the overlays (feature lines, cut outlines,
// ghost lines) over it; the "aovs" and "channels" passes copy sample 0 of every other buffer into
// the single-sample AOVs when those are read (Frame's onRead passes).
//
// Built in two steps: techniques add their channels first (a float per sample with a meaning,
// e.g. Diepstraten03's signed distance), then `declare` makes the targets.
//
//   GBuffer gbuffer;
//   const int channel = gbuffer.addChannel({.name = "cutoutDistance", .meaning = "…"});
//   gbuffer.declare(frame, samples, /*stencil=*/false);
//   frame.addPass({.name = "geometry", .writes = gbuffer.targets(), .run = …});
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cutaway/frame/frame.hpp"
#include "cutaway/gl/objects.hpp"
#include "frame/fullscreen.hpp"

namespace cutaway {

class GBuffer {
 public:
  struct Channel {
    std::string name;     // the AOV's name; the multisample target is "scene" + Name
    std::string meaning;  // of the AOV
  };
  // A coverage buffer blended over the colour in the composite, in the order added.
  struct Overlay {
    Target coverage;                           // single-sample R16F in [0, 1]
    std::function<glm::vec4()> colorOpacity;   // read every frame (live options)
  };

  // Before `declare`: returns the channel's index (its GLSL output is outChannel<i>).
  int addChannel(Channel channel);
  void declare(Frame& frame, int samples, bool stencil);

  // The geometry pass's targets: the colour attachments in order, then the depth.
  std::vector<Target> targets() const;
  // The colour attachments alone (what passes drawing after the geometry pass add to).
  std::vector<Target> colorTargets() const;
  int colorAttachmentCount() const { return int(colorTargets().size()); }
  Target color() const { return color_; }
  Target normal() const { return normal_; }
  Target objectId() const { return objectId_; }
  Target cutMask() const { return cutMask_; }
  Target depth() const { return depth_; }
  int samples() const { return samples_; }

  // Clears every attachment but the colour, and draws the background gradient into it.
  void clearWithBackground(GLuint framebuffer) const;
  // Declarations of the channels' outputs and writeNoChannels() (frame/gbuffer_channels.glsl).
  std::string channelsGlsl() const;
  const std::vector<Channel>& channels() const { return channels_; }

  // The composite pass (the colour and `overlays` in order); then the passes that resolve the
  // other buffers and the channels into their AOVs when they are read, with the frame's
  // uniform buffer (frame/frame_uniforms.glsl) bound again: another renderer sharing the
  // context may have bound its own since.
  void addCompositePass(Frame& frame, std::vector<Overlay> overlays, GLuint frameUniforms);
  // The final colour (RGBA8, single sample).
  Target finalColor() const { return finalColor_; }

 private:
  void addChannelsPass(Frame& frame);
  void addResolvePass(Frame& frame, const std::string& name, const gl::Program& program,
                      std::vector<Target> reads, std::vector<Target> writes);

  std::vector<Channel> channels_;
  std::vector<Target> channelTargets_, channelAovs_;
  std::vector<Overlay> overlays_;
  int samples_ = 1;
  Target color_, normal_, objectId_, cutMask_, depth_;
  GLuint frameUniforms_ = 0;
  Target finalColor_;
  gl::Program backgroundProgram_, compositeProgram_, aovsProgram_, channelsProgram_;
  FullscreenTriangle fullscreen_;
};

}  // namespace cutaway
