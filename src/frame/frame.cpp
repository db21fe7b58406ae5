#include "cutaway/frame/frame.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <vector>

#include "cutaway/core/error.hpp"

namespace cutaway {

namespace {
std::atomic<unsigned> nextFrameSerial{1};

// Bytes per texel and sample of the formats the frame's targets use (what drivers store:
// llvmpipe keeps a depth with stencil in 8 bytes); 16 for any other.
std::uint64_t texelBytes(GLenum format) {
  switch (format) {
    case GL_R8:
      return 1;
    case GL_R16F:
      return 2;
    case GL_RGBA8:
    case GL_R32F:
    case GL_R32I:
    case GL_R32UI:
    case GL_DEPTH_COMPONENT32F:
    case GL_DEPTH_COMPONENT24:
    case GL_DEPTH24_STENCIL8:
      return 4;
    case GL_RGBA16F:
    case GL_RG32F:
    case GL_RG32I:
    case GL_DEPTH32F_STENCIL8:
      return 8;
    default:
      return 16;
  }
}

// A target's bytes: every texel of every sample.
std::uint64_t targetBytes(const TargetDesc& d) {
  return std::uint64_t(d.width) * std::uint64_t(d.height) * std::uint64_t(std::max(d.samples, 1)) *
         texelBytes(d.format);
}

bool isIntegerFormat(GLenum format) {
  return format == GL_R32I || format == GL_RG32I || format == GL_R32UI;
}

std::string mebibytes(std::uint64_t bytes) {
  return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB";
}
}  // namespace

bool isDepthFormat(GLenum format) {
  return format == GL_DEPTH_COMPONENT32F || format == GL_DEPTH_COMPONENT24 ||
         format == GL_DEPTH24_STENCIL8 || format == GL_DEPTH32F_STENCIL8 ||
         format == GL_DEPTH_COMPONENT16;
}

Frame::Frame(int width, int height, const gl::ContextInfo& device,
             std::optional<std::uint64_t> memoryBudget)
    : serial_(nextFrameSerial++),
      width_(width),
      height_(height),
      device_(device),
      // What is free before the first target; the rest of the program needs some of it too.
      budget_(memoryBudget ? *memoryBudget : device.availableMemory() / 10 * 9),
      timer_(device.software) {}

void Frame::checkLimits(const std::string& name, const TargetDesc& d) {
  const std::string size = std::to_string(d.width) + "×" + std::to_string(d.height);
  if (device_.maxTextureSize > 0 && std::max(d.width, d.height) > device_.maxTextureSize)
    throw Error("frame", name,
                "a render target of " + size + " exceeds the device's largest texture, " +
                    std::to_string(device_.maxTextureSize) + " on a side");
  const int maxSamples = isDepthFormat(d.format)     ? device_.maxDepthSamples
                         : isIntegerFormat(d.format) ? device_.maxIntegerSamples
                                                     : device_.maxColorSamples;
  if (d.samples > 1 && maxSamples > 0 && d.samples > maxSamples)
    throw Error("frame", name,
                std::to_string(d.samples) + " samples exceed the device's " +
                    std::to_string(maxSamples) + " for this render target");
  bytes_ += targetBytes(d);
  if (budget_ > 0 && bytes_ > budget_)
    throw Error("frame", name,
                "the render targets need " + mebibytes(bytes_) + " at " + std::to_string(width_) +
                    "×" + std::to_string(height_) + ", more than the " + mebibytes(budget_) +
                    " the device has available" +
                    (device_.software ? " (a software rasteriser keeps them in main memory)" : "") +
                    "; lower the resolution or the samples");
}

Target Frame::declare(const std::string& name, TargetDesc desc) {
  if (find(name)) throw Error("frame", name, "render target declared twice");
  if (desc.width == 0) desc.width = width_;
  if (desc.height == 0) desc.height = height_;
  checkLimits(name, desc);
  gl::Texture texture;
  if (gl::outOfMemory([&] {
        texture = gl::Texture::create2D(desc.format, desc.width, desc.height,
                                        desc.samples > 1 ? desc.samples : 0);
      }))
    throw Error(
        "frame", name,
        "the device could not allocate it (" + mebibytes(targetBytes(desc)) + ", of " +
            mebibytes(bytes_) + " for the render targets at " + std::to_string(width_) + "×" +
            std::to_string(height_) +
            (device_.software ? "; a software rasteriser also limits each texture's size" : "") +
            "); lower the resolution or the samples");
  targets_.push_back(TargetData{name, std::move(desc), std::move(texture)});
  return Target(serial_, int(targets_.size() - 1));
}

void Frame::addPass(PassDesc pass) {
  passes_.push_back(Pass{std::move(pass), {}, 0, 0});
  prepared_ = false;
}

const Frame::TargetData& Frame::target(Target t, const std::string& user) const {
  if (t.frame_ != serial_ || t.index_ < 0 || std::size_t(t.index_) >= targets_.size())
    throw Error("frame", user, "uses a render target of another frame (or none)");
  return targets_[std::size_t(t.index_)];
}

const gl::Texture& Frame::texture(Target t) const {
  const TargetData& data = target(t, "texture");
  runOnRead(t);
  return data.texture;
}

const TargetDesc& Frame::desc(Target t) const {
  return target(t, "desc").desc;
}

std::optional<Target> Frame::find(const std::string& name) const {
  for (std::size_t i = 0; i < targets_.size(); ++i)
    if (targets_[i].name == name) return Target(serial_, int(i));
  return std::nullopt;
}

Target Frame::at(const std::string& name) const {
  if (const auto t = find(name)) return *t;
  throw Error("frame", name, "no such render target");
}

std::vector<float> Frame::read(Target t, int channels) const {
  const TargetData& data = target(t, "read");
  runOnRead(t);
  const TargetDesc& d = data.desc;
  std::vector<float> texels(std::size_t(d.width) * std::size_t(d.height) * std::size_t(channels));
  if (d.format == GL_R32UI) {  // counters and flags written by image stores
    std::vector<GLuint> values(texels.size());
    glGetTextureImage(data.texture.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT,
                      GLsizei(values.size() * sizeof(GLuint)), values.data());
    std::copy(values.begin(), values.end(), texels.begin());
    return texels;
  }
  if (d.format == GL_R32I || d.format == GL_RG32I) {
    const std::vector<GLint> values = readIntegers(t, channels);
    std::copy(values.begin(), values.end(), texels.begin());
    return texels;
  }
  const GLenum format = isDepthFormat(d.format) ? GL_DEPTH_COMPONENT
                        : channels == 4         ? GL_RGBA
                        : channels == 3         ? GL_RGB
                                                : GL_RED;
  glGetTextureImage(data.texture.id(), 0, format, GL_FLOAT,
                    GLsizei(texels.size() * sizeof(float)), texels.data());
  return texels;
}

std::vector<GLint> Frame::readIntegers(Target t, int channels) const {
  const TargetData& data = target(t, "read");
  runOnRead(t);
  const TargetDesc& d = data.desc;
  if (d.format != GL_R32I && d.format != GL_RG32I)
    throw Error("frame", data.name, "not a signed-integer target, read it with read()");
  std::vector<GLint> texels(std::size_t(d.width) * std::size_t(d.height) * std::size_t(channels));
  glGetTextureImage(data.texture.id(), 0, channels == 2 ? GL_RG_INTEGER : GL_RED_INTEGER, GL_INT,
                    GLsizei(texels.size() * sizeof(GLint)), texels.data());
  return texels;
}

std::vector<std::string> Frame::aovNames() const {
  std::vector<std::string> names;
  for (const auto& t : targets_)
    if (!t.desc.meaning.empty()) names.push_back(t.name);
  return names;
}

std::vector<std::string> Frame::passNames() const {
  std::vector<std::string> names;
  for (const auto& p : passes_) names.push_back(p.desc.name);
  return names;
}

void Frame::prepare(Pass& pass) {
  if (!pass.desc.compute) pass.framebuffer = gl::Framebuffer::create();
  std::vector<GLenum> drawBuffers;
  pass.width = width_;
  pass.height = height_;
  bool first = true;
  for (const Target written : pass.desc.writes) {
    const TargetData& t = target(written, pass.desc.name);
    const TargetDesc& d = t.desc;
    if (first) pass.width = d.width, pass.height = d.height;
    if (d.width != pass.width || d.height != pass.height)
      throw Error("frame", pass.desc.name, "writes render targets of different sizes");
    first = false;
    if (pass.desc.compute) continue;
    if (isDepthFormat(d.format)) {
      const bool stencil = d.format == GL_DEPTH24_STENCIL8 || d.format == GL_DEPTH32F_STENCIL8;
      glNamedFramebufferTexture(pass.framebuffer.id(),
                                stencil ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT,
                                t.texture.id(), 0);
    } else {
      const GLenum attachment = GL_COLOR_ATTACHMENT0 + GLenum(drawBuffers.size());
      glNamedFramebufferTexture(pass.framebuffer.id(), attachment, t.texture.id(), 0);
      drawBuffers.push_back(attachment);
    }
  }
  if (pass.desc.compute) return;
  glNamedFramebufferDrawBuffers(pass.framebuffer.id(), GLsizei(drawBuffers.size()),
                                drawBuffers.empty() ? nullptr : drawBuffers.data());
  if (!pass.desc.writes.empty()) {
    const GLenum status = glCheckNamedFramebufferStatus(pass.framebuffer.id(), GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
      throw Error("frame", pass.desc.name,
                  "incomplete framebuffer (status " + std::to_string(status) + ")");
  }
}

void Frame::execute() {
  if (!prepared_) {
    // Per target: written by a pass of every frame, or only by an `onRead` pass.
    enum class Written : char { No, Always, OnRead };
    std::vector<Written> written(targets_.size(), Written::No);
    std::vector<bool> usedOnRead(targets_.size(), false);  // by an onRead pass so far
    for (auto& pass : passes_) {
      for (const Target r : pass.desc.reads) {
        const TargetData& t = target(r, pass.desc.name);
        const Written w = written[std::size_t(r.index_)];
        if (w == Written::No)
          throw Error("frame", pass.desc.name,
                      "reads \"" + t.name + "\" before any pass writes it");
        if (w == Written::OnRead && !pass.desc.onRead)
          throw Error("frame", pass.desc.name,
                      "reads \"" + t.name + "\", which only a pass run on read-back writes");
      }
      prepare(pass);  // validates the written handles
      for (const Target w : pass.desc.writes) {
        if (!pass.desc.onRead && usedOnRead[std::size_t(w.index_)])
          throw Error("frame", pass.desc.name,
                      "writes \"" + targets_[std::size_t(w.index_)].name +
                          "\", which an earlier pass run on read-back uses");
        written[std::size_t(w.index_)] = pass.desc.onRead ? Written::OnRead : Written::Always;
      }
      if (pass.desc.onRead)
        for (const auto& list : {pass.desc.reads, pass.desc.writes})
          for (const Target t : list) usedOnRead[std::size_t(t.index_)] = true;
    }
    prepared_ = true;
  }
  cpuMs_.clear();
  timer_.restart();
  pending_.assign(passes_.size(), false);
  for (std::size_t i = 0; i < passes_.size(); ++i) {
    const Pass& pass = passes_[i];
    if (pass.desc.onRead) {
      pending_[i] = true;
      continue;
    }
    const auto start = std::chrono::steady_clock::now();
    if (timed_) timer_.begin(pass.desc.name);
    run(pass);
    if (timed_) timer_.end();
    cpuMs_.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void Frame::run(const Pass& pass) const {
  if (pass.desc.compute) {
    pass.desc.run(PassContext{pass.width, pass.height, 0});
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
  } else {
    glBindFramebuffer(GL_FRAMEBUFFER, pass.framebuffer.id());
    glViewport(0, 0, pass.width, pass.height);
    pass.desc.run(PassContext{pass.width, pass.height, pass.framebuffer.id()});
  }
}

void Frame::runOnRead(Target t) const {
  for (std::size_t i = 0; i < pending_.size(); ++i) {
    const PassDesc& desc = passes_[i].desc;
    if (!pending_[i] || std::find(desc.writes.begin(), desc.writes.end(), t) == desc.writes.end())
      continue;
    pending_[i] = false;
    for (const Target r : desc.reads) runOnRead(r);
    GLint draw = 0, read = 0, viewport[4];
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read);
    glGetIntegerv(GL_VIEWPORT, viewport);
    run(passes_[i]);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(draw));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(read));
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  }
}

std::vector<PassTiming> Frame::timings() {
  std::vector<PassTiming> out;
  const auto gpu = timer_.collect();
  for (std::size_t i = 0; i < gpu.size(); ++i)
    out.push_back({gpu[i].first, gpu[i].second, i < cpuMs_.size() ? cpuMs_[i] : 0.0});
  return out;
}

}  // namespace cutaway
