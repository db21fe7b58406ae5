#include "frame/gbuffer.hpp"

#include "cutaway/core/error.hpp"
#include "cutaway/gl/shader.hpp"
#include "frame/bindings.hpp"
#include "frame/samples.hpp"

namespace cutaway {

namespace {

// The composite's inputs: unit 0 is the colour, then the overlays (composite.frag).
constexpr int kFirstOverlayUnit = 1;
constexpr int kFirstOverlayLocation = 1;

std::string upperFirst(std::string name) {
  if (!name.empty()) name[0] = char(std::toupper(static_cast<unsigned char>(name[0])));
  return name;
}

}  // namespace

int GBuffer::addChannel(Channel channel) {
  if (color_.valid()) throw Error("gbuffer", channel.name, "a channel added after declare");
  GLint drawBuffers = 0;
  glGetIntegerv(GL_MAX_DRAW_BUFFERS, &drawBuffers);
  if (5 + int(channels_.size()) + 1 > drawBuffers)  // the geometry pass's five fixed outputs
    throw Error("gbuffer", channel.name,
                "more G-buffer channels than this OpenGL's " + std::to_string(drawBuffers) +
                    " draw buffers hold (the active cutters ask for too many)");
  channels_.push_back(std::move(channel));
  return int(channels_.size() - 1);
}

void GBuffer::declare(Frame& f, int samples, bool stencil) {
  samples_ = samples;
  color_ = f.declare("sceneColor", {.format = GL_RGBA8, .samples = samples});
  // The normal and the line weight packed in one word (frame/normal_weight.glsl).
  normal_ = f.declare("sceneNormal", {.format = GL_R32UI, .samples = samples});
  objectId_ = f.declare("sceneObjectId", {.format = GL_RG32I, .samples = samples});
  cutMask_ = f.declare("sceneCutMask", {.format = GL_R8, .samples = samples});
  for (const Channel& c : channels_) {
    channelTargets_.push_back(
        f.declare("scene" + upperFirst(c.name), {.format = GL_R32F, .samples = samples}));
    channelAovs_.push_back(f.declare(c.name, {.format = GL_R32F, .meaning = c.meaning}));
  }
  // Konev18 §6's billboard pipes mark the stencil buffer.
  depth_ = f.declare("sceneDepth",
                     {.format = stencil ? GLenum(GL_DEPTH32F_STENCIL8) : GLenum(GL_DEPTH_COMPONENT32F),
                      .samples = samples});
  backgroundProgram_ = buildFullscreenProgram("frame/background.frag");
}

std::vector<Target> GBuffer::colorTargets() const {
  std::vector<Target> t{color_, normal_, objectId_, cutMask_};
  t.insert(t.end(), channelTargets_.begin(), channelTargets_.end());
  return t;
}

std::vector<Target> GBuffer::targets() const {
  std::vector<Target> t = colorTargets();
  t.push_back(depth_);
  return t;
}

void GBuffer::clearWithBackground(GLuint framebuffer) const {
  const float zero[4] = {0, 0, 0, 0}, one = 1.0f;
  const GLuint noWeight[4] = {0, 0, 0, 0};
  const GLint noObject[4] = {-1, 0, 0, 0};
  const float nan[4] = {std::nanf(""), 0, 0, 0};  // a channel's "no value here"
  glClearNamedFramebufferuiv(framebuffer, GL_COLOR, 1, noWeight);
  glClearNamedFramebufferiv(framebuffer, GL_COLOR, 2, noObject);
  glClearNamedFramebufferfv(framebuffer, GL_COLOR, 3, zero);
  const GLuint attachments = GLuint(colorAttachmentCount());
  for (GLuint i = 4; i < attachments; ++i)
    glClearNamedFramebufferfv(framebuffer, GL_COLOR, GLint(i), nan);
  glClearNamedFramebufferfv(framebuffer, GL_DEPTH, 0, &one);
  // The background gradient into the colour target only.
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  for (GLuint i = 1; i < attachments; ++i) glColorMaski(i, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glUseProgram(backgroundProgram_.id());
  fullscreen_.draw();
  for (GLuint i = 1; i < attachments; ++i) glColorMaski(i, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

std::string GBuffer::channelsGlsl() const {
  std::string glsl, none;
  for (std::size_t i = 0; i < channels_.size(); ++i) {
    const std::string name = "outChannel" + std::to_string(i);
    glsl += "layout(location = " + std::to_string(4 + i) + ") out float " + name + ";  // " +
            channels_[i].name + "\n";
    none += "  " + name + " = uintBitsToFloat(0x7fc00000u);\n";  // NaN: no value here
  }
  return glsl + "void writeNoChannels() {\n" + none + "}\n";
}

void GBuffer::addCompositePass(Frame& f, std::vector<Overlay> overlays, GLuint frameUniforms) {
  frameUniforms_ = frameUniforms;
  overlays_ = std::move(overlays);
  std::string parts;
  std::string blend = "vec3 blendOverlays(ivec2 p, vec3 c) {\n";
  for (std::size_t i = 0; i < overlays_.size(); ++i) {
    const std::string n = std::to_string(i);
    parts += "layout(binding = " + std::to_string(kFirstOverlayUnit + int(i)) +
             ") uniform sampler2D uOverlay" + n + ";\n";
    parts += "layout(location = " + std::to_string(kFirstOverlayLocation + int(i)) +
             ") uniform vec4 uOverlayColor" + n + ";  // rgb, opacity\n";
    blend += "  c = mix(c, uOverlayColor" + n + ".rgb, uOverlayColor" + n +
             ".a * texelFetch(uOverlay" + n + ", p, 0).r);\n";
  }
  blend += "  return c;\n}\n";
  compositeProgram_ =
      gl::buildProgram({.stages = {{GL_VERTEX_SHADER, "frame/fullscreen.vert"},
                                   {GL_FRAGMENT_SHADER, "frame/composite.frag"}},
                        .defines = sampleDefines(samples_),
                        .sources = {{"frame/composite_parts.glsl", parts + blend}}});

  const Target color = f.declare("color", {.format = GL_RGBA8});
  finalColor_ = color;
  const Target normal = f.declare(
      "normal", {.format = GL_RGBA16F,
                 .meaning = "world-space unit normal of the visible surface, turned towards "
                            "the viewer (the cutaway surface's on cut surfaces), to within "
                            "0.06°; (0,0,0) on background; sample 0",
                 .aovChannels = 3});
  const Target position =
      f.declare("position", {.format = GL_RGBA32F,
                             .meaning = "world-space position of the visible surface, scene units; "
                                        "(0,0,0) on background; sample 0",
                             .aovChannels = 3});
  const Target viewDepth =
      f.declare("viewDepth", {.format = GL_R32F,
                              .meaning = "linear eye-space depth: distance from the eye along the "
                                         "viewing direction, scene units; 0 on background; "
                                         "sample 0"});
  const Target objectId = f.declare(
      "objectId", {.format = GL_R32F,
                   .meaning = "index of the visible object in the scene's object list (as "
                              "printed by `cutaway info`); -1 on background; sample 0"});
  const Target depth =
      f.declare("depth", {.format = GL_R32F,
                          .meaning = "window-space depth in [0,1] (OpenGL default depth range, "
                                     "0 = near plane, 1 = far plane and background); sample 0"});
  const Target cutMask =
      f.declare("cutMask", {.format = GL_R32F,
                            .meaning = "1 where a cut surface or cut wall is shown (a back face of "
                                       "a solid seen through the cut: Burns08 §4.1, Diepstraten03 "
                                       "rule 5), else 0; sample 0"});
  std::vector<Target> reads{color_};
  for (const Overlay& o : overlays_) reads.push_back(o.coverage);
  f.addPass({.name = "composite",
             .reads = reads,
             .writes = {color},
             .run = [this, &f, reads](const PassContext&) {
               const GLuint program = compositeProgram_.id();
               glDisable(GL_DEPTH_TEST);
               glUseProgram(program);
               for (std::size_t unit = 0; unit < reads.size(); ++unit)
                 glBindTextureUnit(GLuint(unit), f.texture(reads[unit]).id());
               glProgramUniform1i(program, 0, samples_);
               for (std::size_t i = 0; i < overlays_.size(); ++i) {
                 const glm::vec4 c = overlays_[i].colorOpacity();
                 glProgramUniform4fv(program, kFirstOverlayLocation + GLint(i), 1, &c[0]);
               }
               fullscreen_.draw();
             }});
  // Six full-size buffers that only AOVs and inspectors use: resolved when read.
  aovsProgram_ = gl::buildProgram({.stages = {{GL_VERTEX_SHADER, "frame/fullscreen.vert"},
                                              {GL_FRAGMENT_SHADER, "frame/aovs.frag"}},
                                   .defines = sampleDefines(samples_)});
  addResolvePass(f, "aovs", aovsProgram_, {normal_, objectId_, depth_, cutMask_},
                 {normal, position, viewDepth, objectId, depth, cutMask});
  addChannelsPass(f);
}

// A full-screen pass run when its outputs are read: `reads` on texture units 0, 1, … in order.
void GBuffer::addResolvePass(Frame& f, const std::string& name, const gl::Program& program,
                             std::vector<Target> reads, std::vector<Target> writes) {
  f.addPass({.name = name,
             .reads = reads,
             .writes = std::move(writes),
             .run =
                 [this, &f, &program, reads](const PassContext&) {
                   glDisable(GL_DEPTH_TEST);
                   glUseProgram(program.id());
                   glBindBufferBase(GL_UNIFORM_BUFFER, Bindings::kFrameUniformBlock,
                                    frameUniforms_);
                   for (std::size_t unit = 0; unit < reads.size(); ++unit)
                     glBindTextureUnit(GLuint(unit), f.texture(reads[unit]).id());
                   fullscreen_.draw();
                 },
             .onRead = true});
}

// The channels' AOVs in a pass of their own: with the aovs pass's six outputs they would
// exceed the eight draw buffers an implementation may stop at (llvmpipe does).
void GBuffer::addChannelsPass(Frame& f) {
  if (channels_.empty()) return;
  std::string parts, copy = "void copyChannels(ivec2 p) {\n";
  for (std::size_t i = 0; i < channels_.size(); ++i) {
    const std::string n = std::to_string(i);
    parts += "layout(binding = " + n + ") uniform SAMPLER_MS uChannel" + n + ";\n";
    parts += "layout(location = " + n + ") out float outChannel" + n + ";  // " + channels_[i].name + "\n";
    copy += "  outChannel" + n + " = texelFetch(uChannel" + n + ", p, 0).r;\n";
  }
  copy += "}\n";
  channelsProgram_ = gl::buildProgram({.stages = {{GL_VERTEX_SHADER, "frame/fullscreen.vert"},
                                                  {GL_FRAGMENT_SHADER, "frame/channels.frag"}},
                                       .defines = sampleDefines(samples_),
                                       .sources = {{"frame/channel_parts.glsl", parts + copy}}});
  addResolvePass(f, "channels", channelsProgram_, channelTargets_, channelAovs_);
}

}  // namespace cutaway
