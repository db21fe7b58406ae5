#include "cutaway/render/renderer.hpp"

#include <cstring>

#include "cutaway/core/error.hpp"
#include "cutaway/gl/shader.hpp"

namespace cutaway {

namespace {

// std140 mirror of src/render/frame_uniforms.glsl.
struct FrameUniforms {
  glm::mat4 view, projection, viewProjection;
  glm::vec4 eye, forward;
  glm::vec4 lightVector[8];
  glm::vec4 lightColor[8];
  glm::ivec4 counts;
  glm::vec4 backgroundTop, backgroundBottom;
  glm::vec4 goochCool, goochWarm;
  glm::vec4 styleParams;
};

struct GpuMesh {
  gl::VertexArray vertexArray;
  gl::Buffer vertices, indices;
  GLsizei indexCount = 0;
};

GpuMesh upload(const Mesh& mesh) {
  std::vector<float> interleaved;
  interleaved.reserve(mesh.positions.size() * 6);
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const auto& p = mesh.positions[i];
    const auto& n = mesh.normals[i];
    interleaved.insert(interleaved.end(), {p.x, p.y, p.z, n.x, n.y, n.z});
  }
  GpuMesh g;
  g.vertices = gl::Buffer::create(GLsizeiptr(interleaved.size() * sizeof(float)), interleaved.data());
  g.indices = gl::Buffer::create(GLsizeiptr(mesh.triangles.size() * sizeof(glm::uvec3)),
                                 mesh.triangles.data());
  g.indexCount = GLsizei(mesh.triangles.size() * 3);
  g.vertexArray = gl::VertexArray::create();
  const GLuint vao = g.vertexArray.id();
  glVertexArrayVertexBuffer(vao, 0, g.vertices.id(), 0, 6 * sizeof(float));
  glVertexArrayElementBuffer(vao, g.indices.id());
  glEnableVertexArrayAttrib(vao, 0);
  glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(vao, 0, 0);
  glEnableVertexArrayAttrib(vao, 1);
  glVertexArrayAttribFormat(vao, 1, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float));
  glVertexArrayAttribBinding(vao, 1, 0);
  return g;
}

const char* styleFile(const std::string& style) {
  if (style == "gooch") return "styles/gooch/gooch.glsl";
  if (style == "blinn-phong") return "styles/blinn_phong/blinn_phong.glsl";
  throw Error("style", "", "unknown style \"" + style + "\"");
}

}  // namespace

struct Renderer::Impl {
  std::vector<GpuMesh> meshes;  // per scene object; empty for proxies
  gl::Buffer frameUniforms;
  gl::VertexArray emptyVertexArray;
  gl::Program meshProgram, backgroundProgram, linesProgram, compositeProgram;
};

Renderer::Renderer(const Scene& scene, const gl::ContextInfo& info)
    : scene_(scene), impl_(std::make_unique<Impl>()) {
  Impl& g = *impl_;
  for (const auto& object : scene.objects)
    g.meshes.push_back(object.proxy ? GpuMesh{} : upload(*object.mesh));
  g.frameUniforms = gl::Buffer::create(sizeof(FrameUniforms), nullptr, GL_DYNAMIC_STORAGE_BIT);
  g.emptyVertexArray = gl::VertexArray::create();
  g.meshProgram = gl::buildProgram({.stages = {{GL_VERTEX_SHADER, "render/mesh.vert"},
                                               {GL_FRAGMENT_SHADER, "render/mesh.frag"}},
                                    .aliases = {{"style.glsl", styleFile(scene.style.name)}}});
  g.backgroundProgram = gl::buildProgram({.stages = {{GL_VERTEX_SHADER, "render/fullscreen.vert"},
                                                     {GL_FRAGMENT_SHADER, "render/background.frag"}}});
  g.compositeProgram = gl::buildProgram({.stages = {{GL_VERTEX_SHADER, "render/fullscreen.vert"},
                                                    {GL_FRAGMENT_SHADER, "render/composite.frag"}}});
  const bool lines = scene.style.lines.has_value();
  if (lines)
    g.linesProgram = gl::buildProgram({.stages = {{GL_VERTEX_SHADER, "render/fullscreen.vert"},
                                                  {GL_FRAGMENT_SHADER, "styles/lines/lines.frag"}}});

  const int samples = scene.samples;
  frame_ = std::make_unique<Frame>(scene.width, scene.height, info.software);
  Frame& f = *frame_;
  f.declare("sceneColor", {.format = GL_RGBA8, .samples = samples});
  f.declare("sceneNormal", {.format = GL_RGBA16F, .samples = samples});
  f.declare("scenePosition", {.format = GL_RGBA32F, .samples = samples});
  f.declare("sceneObjectId", {.format = GL_R32I, .samples = samples});
  f.declare("sceneDepth", {.format = GL_DEPTH_COMPONENT32F, .samples = samples});
  if (lines)
    f.declare("lines", {.format = GL_R16F,
                        .meaning = "feature-line coverage in [0,1] (silhouettes and creases, "
                                   "fraction of MSAA samples on a line)"});
  f.declare("color", {.format = GL_RGBA8});
  f.declare("normal", {.format = GL_RGBA16F,
                       .meaning = "world-space unit normal of the visible surface, turned towards "
                                  "the viewer; (0,0,0) on background; sample 0",
                       .aovChannels = 3});
  f.declare("position", {.format = GL_RGBA32F,
                         .meaning = "world-space position of the visible surface, scene units; "
                                    "(0,0,0) on background; sample 0",
                         .aovChannels = 3});
  f.declare("viewDepth", {.format = GL_R32F,
                          .meaning = "linear eye-space depth: distance from the eye along the "
                                     "viewing direction, scene units; 0 on background; sample 0"});
  f.declare("objectId", {.format = GL_R32F,
                         .meaning = "index of the visible object in the scene's object list (as "
                                    "printed by `cutaway info`); -1 on background; sample 0"});
  f.declare("depth", {.format = GL_R32F,
                      .meaning = "window-space depth in [0,1] (OpenGL default depth range, "
                                 "0 = near plane, 1 = far plane and background); sample 0"});

  f.addPass({.name = "geometry",
             .writes = {"sceneColor", "sceneNormal", "scenePosition", "sceneObjectId", "sceneDepth"},
             .run = [this](const PassContext& pass) {
               const Impl& g = *impl_;
               const float zero[4] = {0, 0, 0, 0}, one = 1.0f;
               const GLint noObject[4] = {-1, 0, 0, 0};
               glClearNamedFramebufferfv(pass.framebuffer, GL_COLOR, 1, zero);
               glClearNamedFramebufferfv(pass.framebuffer, GL_COLOR, 2, zero);
               glClearNamedFramebufferiv(pass.framebuffer, GL_COLOR, 3, noObject);
               glClearNamedFramebufferfv(pass.framebuffer, GL_DEPTH, 0, &one);
               // Background gradient into the colour target only.
               glDisable(GL_DEPTH_TEST);
               glDisable(GL_CULL_FACE);
               glColorMaski(1, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
               glColorMaski(2, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
               glColorMaski(3, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
               glUseProgram(g.backgroundProgram.id());
               glBindVertexArray(g.emptyVertexArray.id());
               glDrawArrays(GL_TRIANGLES, 0, 3);
               for (GLuint i = 1; i < 4; ++i) glColorMaski(i, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);

               glEnable(GL_DEPTH_TEST);
               glDepthFunc(GL_LESS);
               glDepthMask(GL_TRUE);
               glEnable(GL_MULTISAMPLE);
               const GLuint program = g.meshProgram.id();
               glUseProgram(program);
               for (std::size_t i = 0; i < scene_.objects.size(); ++i) {
                 const SceneObject& o = scene_.objects[i];
                 if (o.proxy) continue;
                 const glm::mat4 normalMatrix = glm::transpose(glm::inverse(o.transform));
                 glProgramUniformMatrix4fv(program, 0, 1, GL_FALSE, &o.transform[0][0]);
                 glProgramUniformMatrix4fv(program, 4, 1, GL_FALSE, &normalMatrix[0][0]);
                 glProgramUniform3fv(program, 8, 1, &o.material.color[0]);
                 glProgramUniform1f(program, 9, o.material.specular);
                 glProgramUniform1f(program, 10, o.material.shininess);
                 glProgramUniform1i(program, 11, int(i));
                 const auto lines = o.params.find("lines");
                 const bool objectLines = lines == o.params.end() || std::get<bool>(lines->second);
                 glProgramUniform1f(program, 12, objectLines ? 1.0f : 0.0f);
                 glBindVertexArray(g.meshes[i].vertexArray.id());
                 glDrawElements(GL_TRIANGLES, g.meshes[i].indexCount, GL_UNSIGNED_INT, nullptr);
               }
             }});
  if (lines)
    f.addPass({.name = "lines",
               .reads = {"sceneNormal", "scenePosition", "sceneObjectId"},
               .writes = {"lines"},
               .run = [this](const PassContext&) {
                 const Impl& g = *impl_;
                 const LineStyle& l = *scene_.style.lines;
                 const GLuint program = g.linesProgram.id();
                 glDisable(GL_DEPTH_TEST);
                 glUseProgram(program);
                 glBindTextureUnit(0, frame_->texture("sceneNormal").id());
                 glBindTextureUnit(1, frame_->texture("scenePosition").id());
                 glBindTextureUnit(2, frame_->texture("sceneObjectId").id());
                 glProgramUniform1i(program, 0, scene_.samples);
                 glProgramUniform1i(program, 1, std::max(1, int(std::lround(l.width))));
                 glProgramUniform1f(program, 2, std::cos(glm::radians(l.creaseAngle)));
                 glProgramUniform1f(program, 3, l.depthThreshold);
                 glProgramUniform1i(program, 4, l.silhouettes ? 1 : 0);
                 glProgramUniform1i(program, 5, l.creases ? 1 : 0);
                 glBindVertexArray(g.emptyVertexArray.id());
                 glDrawArrays(GL_TRIANGLES, 0, 3);
               }});
  std::vector<std::string> compositeReads{"sceneColor", "sceneNormal", "scenePosition",
                                          "sceneObjectId", "sceneDepth"};
  if (lines) compositeReads.push_back("lines");
  f.addPass({.name = "composite",
             .reads = compositeReads,
             .writes = {"color", "normal", "position", "viewDepth", "objectId", "depth"},
             .run = [this, lines](const PassContext&) {
               const Impl& g = *impl_;
               const GLuint program = g.compositeProgram.id();
               glDisable(GL_DEPTH_TEST);
               glUseProgram(program);
               const char* inputs[] = {"sceneColor", "sceneNormal", "scenePosition",
                                       "sceneObjectId", "sceneDepth"};
               for (GLuint unit = 0; unit < 5; ++unit)
                 glBindTextureUnit(unit, frame_->texture(inputs[unit]).id());
               if (lines) glBindTextureUnit(5, frame_->texture("lines").id());
               glProgramUniform1i(program, 0, scene_.samples);
               glProgramUniform1i(program, 1, lines ? 1 : 0);
               if (lines) glProgramUniform3fv(program, 2, 1, &scene_.style.lines->color[0]);
               glBindVertexArray(g.emptyVertexArray.id());
               glDrawArrays(GL_TRIANGLES, 0, 3);
             }});
}

Renderer::~Renderer() = default;

void Renderer::render(const Camera& camera) {
  const float aspect = float(scene_.width) / float(scene_.height);
  FrameUniforms u{};
  u.view = camera.view();
  u.projection = camera.projectionMatrix(aspect);
  u.viewProjection = u.projection * u.view;
  u.eye = glm::vec4(camera.eye, 1.0f);
  u.forward = glm::vec4(glm::normalize(camera.target - camera.eye), 0.0f);
  const glm::mat4 cameraToWorld = glm::inverse(u.view);
  int count = 0;
  for (const auto& light : scene_.lights) {
    if (count == 8) break;
    const bool point = light.type == Light::Type::Point;
    glm::vec4 v = point ? glm::vec4(light.position, 1.0f) : glm::vec4(light.direction, 0.0f);
    if (light.cameraSpace) v = cameraToWorld * v;
    u.lightVector[count] = v;
    u.lightColor[count] = glm::vec4(light.color * light.intensity, 1.0f);
    ++count;
  }
  u.counts = glm::ivec4(count, camera.projection == Projection::Orthographic ? 1 : 0, 0, 0);
  u.backgroundTop = glm::vec4(scene_.backgroundTop, 1.0f);
  u.backgroundBottom = glm::vec4(scene_.backgroundBottom, 1.0f);
  u.goochCool = glm::vec4(scene_.style.gooch.cool, scene_.style.gooch.alpha);
  u.goochWarm = glm::vec4(scene_.style.gooch.warm, scene_.style.gooch.beta);
  u.styleParams = glm::vec4(scene_.style.blinnPhong.ambient, 0, 0, 0);
  glNamedBufferSubData(impl_->frameUniforms.id(), 0, sizeof u, &u);
  glBindBufferBase(GL_UNIFORM_BUFFER, 0, impl_->frameUniforms.id());
  frame_->execute();
}

GLuint Renderer::colorTexture() const { return frame_->texture("color").id(); }

Rgba8Image Renderer::readColor() const {
  Rgba8Image image(frame_->width(), frame_->height());
  glGetTextureImage(colorTexture(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(image.pixels.size()),
                    image.pixels.data());
  image.flipVertically();
  return image;
}

std::vector<Aov> Renderer::readAovs() const {
  std::vector<Aov> aovs;
  for (const auto& name : frame_->aovNames()) {
    const TargetDesc& d = frame_->desc(name);
    const int channels = d.aovChannels ? d.aovChannels : 1;
    FloatImage image(d.width, d.height, channels);
    glGetTextureImage(frame_->texture(name).id(), 0, channels == 3 ? GL_RGB : GL_RED, GL_FLOAT,
                      GLsizei(image.data.size() * sizeof(float)), image.data.data());
    image.flipVertically();
    aovs.push_back({name, d.meaning, std::move(image)});
  }
  return aovs;
}

}  // namespace cutaway
