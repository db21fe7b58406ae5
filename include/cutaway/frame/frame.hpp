// cutaway/frame/frame.hpp — a frame as a sequence of named passes over render targets.
//
// A frame owns its render targets (textures with a format, a size and, for AOVs, a meaning)
// and a list of passes. `declare` returns a typed handle to the new target; a pass names the
// targets it reads and writes by their handles, and `execute` checks that every read was
// written by an earlier pass, binds a framebuffer with the written targets attached (colour
// targets in the order given, a depth-format target as the depth attachment), sets the
// viewport and times the pass with GL_TIME_ELAPSED. Targets keep their names for the AOV
// dumps and for tools that look them up (`find`).
//
//   cutaway::Frame frame(640, 480, context.info().software);
//   const cutaway::Target color = frame.declare("color", {.format = GL_RGBA8});
//   frame.addPass({.name = "background", .writes = {color},
//                  .run = [](const cutaway::PassContext&) { /* draw */ }});
//   frame.execute();
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cutaway/gl/context.hpp"
#include "cutaway/gl/objects.hpp"
#include "cutaway/gl/timer.hpp"

namespace cutaway {

struct TargetDesc {
  GLenum format = GL_RGBA8;
  // 0: a resolved target; ≥ 1: one of the frame's per-sample targets, a multisample texture
  // from 2 samples up and a plain 2-D one at 1 (llvmpipe rasterises into a one-sample
  // multisample texture about 3× slower). Programs that read them: frame/samples.hpp.
  int samples = 0;
  GLenum textureTarget() const { return samples > 1 ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D; }
  int width = 0, height = 0;  // 0: the frame's size
  // For AOV dumps: what a texel means (units, conventions); empty = not an AOV.
  std::string meaning;
  int aovChannels = 0;  // channels written to the PFM (1 or 3); 0 = derived from the format
};

// A render target of one frame. Only `Frame::declare` makes valid handles, so a pass cannot
// name a target that does not exist; a handle carries its frame, so it cannot be used with
// another one.
class Target {
 public:
  Target() = default;
  bool valid() const { return index_ >= 0; }
  friend bool operator==(Target, Target) = default;

 private:
  friend class Frame;
  Target(unsigned frame, int index) : frame_(frame), index_(index) {}
  unsigned frame_ = 0;
  int index_ = -1;
};

struct PassContext {
  int width, height;  // viewport of this pass (a compute pass: the size of what it writes)
  GLuint framebuffer;  // 0 for a compute pass
};

struct PassDesc {
  std::string name;
  std::vector<Target> reads, writes;
  std::function<void(const PassContext&)> run;
  // A compute pass dispatches instead of drawing and writes its targets as images
  // (imageStore): it gets no framebuffer, and the frame puts a memory barrier after it so
  // that later passes and read-backs see what it wrote.
  bool compute = false;
  // Runs not in `execute` but when one of its targets is read back (`read`, `texture` from
  // outside the passes), at most once per `execute`: for resolves that only AOVs and
  // inspectors use, which a frame that only shows its picture skips. Untimed. Only other
  // such passes may read what it writes, and no later pass of every frame may write what it
  // reads or writes (it would see that pass's result, not the one before).
  bool onRead = false;
};

struct PassTiming {
  std::string name;
  double gpuMs;  // GL_TIME_ELAPSED
  double cpuMs;  // wall time of the pass's own code (CPU kernels, command submission)
};

class Frame {
 public:
  // Its targets are held to the limits of `device` (its context's): sizes, samples, and
  // memory: `memoryBudget` bytes for all of them, by default nine tenths of what the device
  // has available now (no limit when it does not say).
  Frame(int width, int height, const gl::ContextInfo& device,
        std::optional<std::uint64_t> memoryBudget = std::nullopt);
  // Throws cutaway::Error for a name declared twice, and for a target beyond the device's
  // limits (its size or samples, or memory: the targets together must fit in what the
  // device had available when the frame was made, and the device must give it).
  [[nodiscard]] Target declare(const std::string& name, TargetDesc desc);
  void addPass(PassDesc pass);
  // Runs every pass once; throws cutaway::Error for an ill-formed frame (a read before its
  // write, a handle of another frame, an incomplete framebuffer).
  void execute();
  // GPU time of each pass in the last `execute` (waits for the queries); empty untimed.
  std::vector<PassTiming> timings();
  // Whether `execute` times its passes with GL_TIME_ELAPSED queries (on by default); off, a
  // frame can run inside another application's own timer query.
  void setTimed(bool timed) { timed_ = timed; }
  // The passes' names in execution order.
  std::vector<std::string> passNames() const;

  // A target's texture, after the `onRead` passes that write it have run for this frame. Running
  // one changes what a pass changes (program, texture units, switches) but the framebuffer
  // bindings and the viewport, which come back; a pass that draws may not call it for a target
  // it did not declare.
  const gl::Texture& texture(Target target) const;
  const TargetDesc& desc(Target target) const;
  // A single-sample target's texels as floats, `channels` (1: red, 3: RGB, 4: RGBA) per
  // texel, rows bottom to top as OpenGL stores them; runs the `onRead` passes as `texture`.
  std::vector<float> read(Target target, int channels) const;
  // A single-sample signed-integer target's texels (GL_R32I, GL_RG32I), `channels` (1: red,
  // 2: red and green) per texel, as `read`.
  std::vector<GLint> readIntegers(Target target, int channels) const;

  // Lookup by name, for tools outside the frame's passes (AOV inspectors, tests).
  std::optional<Target> find(const std::string& name) const;
  Target at(const std::string& name) const;  // throws cutaway::Error when there is none
  bool has(const std::string& name) const { return find(name).has_value(); }
  const gl::Texture& texture(const std::string& name) const { return texture(at(name)); }
  const TargetDesc& desc(const std::string& name) const { return desc(at(name)); }
  std::vector<float> read(const std::string& name, int channels) const {
    return read(at(name), channels);
  }
  std::vector<GLint> readIntegers(const std::string& name, int channels) const {
    return readIntegers(at(name), channels);
  }
  // Targets with a meaning, in declaration order.
  std::vector<std::string> aovNames() const;
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  struct TargetData {
    std::string name;
    TargetDesc desc;
    gl::Texture texture;
  };
  struct Pass {
    PassDesc desc;
    gl::Framebuffer framebuffer;
    int width = 0, height = 0;
  };
  const TargetData& target(Target t, const std::string& user) const;
  void prepare(Pass& pass);
  void run(const Pass& pass) const;
  // Runs the pending `onRead` passes (and those they read from) that write `t`.
  void runOnRead(Target t) const;

  void checkLimits(const std::string& name, const TargetDesc& desc);

  unsigned serial_;  // this frame's handles carry it
  int width_, height_;
  gl::ContextInfo device_;
  std::uint64_t budget_ = 0, bytes_ = 0;  // memory for the targets (0: unknown), and used
  gl::PassTimer timer_;
  std::vector<TargetData> targets_;  // in declaration order, indexed by Target
  std::vector<Pass> passes_;
  std::vector<double> cpuMs_;
  bool prepared_ = false;
  bool timed_ = true;
  mutable std::vector<bool> pending_;  // per pass: an `onRead` pass not run since `execute`
};

// Whether `format` is a depth format (attached as GL_DEPTH_ATTACHMENT).
bool isDepthFormat(GLenum format);

}  // namespace cutaway
