#include "cutaway/render/frame.hpp"

#include <algorithm>
#include <chrono>
#include <set>

#include "cutaway/core/error.hpp"

namespace cutaway {

bool isDepthFormat(GLenum format) {
  return format == GL_DEPTH_COMPONENT32F || format == GL_DEPTH_COMPONENT24 ||
         format == GL_DEPTH24_STENCIL8 || format == GL_DEPTH32F_STENCIL8 ||
         format == GL_DEPTH_COMPONENT16;
}

Frame::Frame(int width, int height, bool software)
    : width_(width), height_(height), timer_(software) {}

void Frame::declare(const std::string& name, TargetDesc desc) {
  if (targets_.count(name)) throw Error("frame", name, "render target declared twice");
  if (desc.width == 0) desc.width = width_;
  if (desc.height == 0) desc.height = height_;
  gl::Texture texture = gl::Texture::create2D(desc.format, desc.width, desc.height, desc.samples);
  targets_.emplace(name, Target{std::move(desc), std::move(texture)});
  order_.push_back(name);
}

void Frame::addPass(PassDesc pass) {
  passes_.push_back(Pass{std::move(pass), {}, 0, 0});
  prepared_ = false;
}

const gl::Texture& Frame::texture(const std::string& name) const {
  const auto it = targets_.find(name);
  if (it == targets_.end()) throw Error("frame", name, "no such render target");
  return it->second.texture;
}

std::vector<float> Frame::read(const std::string& name, int channels) const {
  const TargetDesc& d = desc(name);
  std::vector<float> texels(std::size_t(d.width) * std::size_t(d.height) * std::size_t(channels));
  if (d.format == GL_R32UI) {  // counters and flags written by image stores
    std::vector<GLuint> values(texels.size());
    glGetTextureImage(texture(name).id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT,
                      GLsizei(values.size() * sizeof(GLuint)), values.data());
    std::copy(values.begin(), values.end(), texels.begin());
    return texels;
  }
  const GLenum format = isDepthFormat(d.format) ? GL_DEPTH_COMPONENT
                        : channels == 3         ? GL_RGB
                                                : GL_RED;
  glGetTextureImage(texture(name).id(), 0, format, GL_FLOAT, GLsizei(texels.size() * sizeof(float)),
                    texels.data());
  return texels;
}

const TargetDesc& Frame::desc(const std::string& name) const {
  const auto it = targets_.find(name);
  if (it == targets_.end()) throw Error("frame", name, "no such render target");
  return it->second.desc;
}

std::vector<std::string> Frame::aovNames() const {
  std::vector<std::string> names;
  for (const auto& n : order_)
    if (!targets_.at(n).desc.meaning.empty()) names.push_back(n);
  return names;
}

void Frame::prepare(Pass& pass) {
  pass.framebuffer = gl::Framebuffer::create();
  std::vector<GLenum> drawBuffers;
  pass.width = width_;
  pass.height = height_;
  bool first = true;
  for (const auto& name : pass.desc.writes) {
    const auto it = targets_.find(name);
    if (it == targets_.end())
      throw Error("frame", pass.desc.name, "writes undeclared render target \"" + name + "\"");
    const TargetDesc& d = it->second.desc;
    if (first) pass.width = d.width, pass.height = d.height;
    if (d.width != pass.width || d.height != pass.height)
      throw Error("frame", pass.desc.name, "writes render targets of different sizes");
    first = false;
    if (isDepthFormat(d.format)) {
      const bool stencil = d.format == GL_DEPTH24_STENCIL8 || d.format == GL_DEPTH32F_STENCIL8;
      glNamedFramebufferTexture(pass.framebuffer.id(),
                                stencil ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT,
                                it->second.texture.id(), 0);
    } else {
      const GLenum attachment = GL_COLOR_ATTACHMENT0 + GLenum(drawBuffers.size());
      glNamedFramebufferTexture(pass.framebuffer.id(), attachment, it->second.texture.id(), 0);
      drawBuffers.push_back(attachment);
    }
  }
  glNamedFramebufferDrawBuffers(pass.framebuffer.id(), GLsizei(drawBuffers.size()),
                                drawBuffers.empty() ? nullptr : drawBuffers.data());
  if (!drawBuffers.empty() || !pass.desc.writes.empty()) {
    const GLenum status = glCheckNamedFramebufferStatus(pass.framebuffer.id(), GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
      throw Error("frame", pass.desc.name,
                  "incomplete framebuffer (status " + std::to_string(status) + ")");
  }
}

void Frame::execute() {
  if (!prepared_) {
    std::set<std::string> written;
    for (auto& pass : passes_) {
      for (const auto& r : pass.desc.reads) {
        if (!targets_.count(r))
          throw Error("frame", pass.desc.name, "reads undeclared render target \"" + r + "\"");
        if (!written.count(r))
          throw Error("frame", pass.desc.name, "reads \"" + r + "\" before any pass writes it");
      }
      for (const auto& w : pass.desc.writes) written.insert(w);
      prepare(pass);
    }
    prepared_ = true;
  }
  cpuMs_.clear();
  for (auto& pass : passes_) {
    const auto start = std::chrono::steady_clock::now();
    timer_.begin(pass.desc.name);
    glBindFramebuffer(GL_FRAMEBUFFER, pass.framebuffer.id());
    glViewport(0, 0, pass.width, pass.height);
    pass.desc.run(PassContext{pass.width, pass.height, pass.framebuffer.id()});
    timer_.end();
    cpuMs_.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

std::vector<PassTiming> Frame::timings() {
  std::vector<PassTiming> out;
  const auto gpu = timer_.collect();
  for (std::size_t i = 0; i < gpu.size(); ++i)
    out.push_back({gpu[i].first, gpu[i].second, i < cpuMs_.size() ? cpuMs_[i] : 0.0});
  return out;
}

}  // namespace cutaway
