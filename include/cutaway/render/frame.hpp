// cutaway/render/frame.hpp — a frame as a sequence of named passes over render targets.
//
// A frame owns its render targets (textures with a format, a size and, for AOVs, a meaning)
// and a list of passes. Each pass declares what it reads and what it writes; `execute`
// checks that every read was written by an earlier pass, binds a framebuffer with the
// written targets attached (colour targets in declaration order, a depth-format target as
// the depth attachment), sets the viewport and times the pass with GL_TIME_ELAPSED.
//
//   cutaway::Frame frame(640, 480, context.info().software);
//   frame.declare("color", {.format = GL_RGBA8});
//   frame.addPass({.name = "background", .writes = {"color"}, .run = [](const PassContext&) { ...
//   }}); frame.execute();
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "cutaway/gl/objects.hpp"
#include "cutaway/gl/timer.hpp"

namespace cutaway {

struct TargetDesc {
  GLenum format = GL_RGBA8;
  int samples = 0;            // 0: a plain 2-D texture; ≥ 1: a multisample texture
  int width = 0, height = 0;  // 0: the frame's size
  // For AOV dumps: what a texel means (units, conventions); empty = not an AOV.
  std::string meaning;
  int aovChannels = 0;  // channels written to the PFM (1 or 3); 0 = derived from the format
};

struct PassContext {
  int width, height;  // viewport of this pass
  GLuint framebuffer;
};

struct PassDesc {
  std::string name;
  std::vector<std::string> reads, writes;
  std::function<void(const PassContext&)> run;
};

struct PassTiming {
  std::string name;
  double gpuMs;  // GL_TIME_ELAPSED
  double cpuMs;  // wall time of the pass's own code (CPU kernels, command submission)
};

class Frame {
 public:
  Frame(int width, int height, bool software);
  void declare(const std::string& name, TargetDesc desc);
  void addPass(PassDesc pass);
  // Runs every pass once; throws cutaway::Error for an ill-formed frame (a read before its
  // write, an undeclared target, an incomplete framebuffer).
  void execute();
  // GPU time of each pass in the last `execute` (waits for the queries).
  std::vector<PassTiming> timings();

  const gl::Texture& texture(const std::string& name) const;
  // A single-sample target's texels as floats, `channels` (1: red, 3: RGB) per texel, rows
  // bottom to top as OpenGL stores them.
  std::vector<float> read(const std::string& name, int channels) const;
  const TargetDesc& desc(const std::string& name) const;
  bool has(const std::string& name) const { return targets_.count(name) != 0; }
  // Targets with a meaning, in declaration order.
  std::vector<std::string> aovNames() const;
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  struct Target {
    TargetDesc desc;
    gl::Texture texture;
  };
  struct Pass {
    PassDesc desc;
    gl::Framebuffer framebuffer;
    int width = 0, height = 0;
  };
  void prepare(Pass& pass);

  int width_, height_;
  gl::PassTimer timer_;
  std::map<std::string, Target> targets_;
  std::vector<std::string> order_;
  std::vector<Pass> passes_;
  std::vector<double> cpuMs_;
  bool prepared_ = false;
};

// Whether `format` is a depth format (attached as GL_DEPTH_ATTACHMENT).
bool isDepthFormat(GLenum format);

}  // namespace cutaway
