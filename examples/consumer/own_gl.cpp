// An application that draws its own OpenGL 4.5 scene (a ball inside a closed box) and uses
// one technique of the library: the adaptive cutaway surface (Burns08), computed from the
// ball's depth, opens the box in front of it. Everything else is the application's own GL.
//   own-gl OUT.png
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <epoxy/gl.h>
#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cutaway/core/error.hpp>
#include <cutaway/core/image.hpp>
#include <cutaway/cutters/adaptive_surface.hpp>
#include <cutaway/gl/context.hpp>

namespace {

constexpr int kWidth = 640, kHeight = 480;

const char* kVertex = R"(#version 450 core
layout(location = 0) in vec3 aPosition;
layout(location = 0) uniform mat4 uViewProjection;
out vec3 vPosition;
void main() { vPosition = aPosition; gl_Position = uViewProjection * vec4(aPosition, 1.0); })";

// Lambert shading under a head light; with uCut, what lies in front of the cutaway surface is
// discarded (back faces against the dilated surface, Burns08 §4.2), and the box's inside, seen
// through the opening, is drawn darker.
const char* kFragment = R"(#version 450 core
in vec3 vPosition;
layout(location = 1) uniform vec3 uColor;
layout(location = 2) uniform int uCut;
layout(location = 3) uniform vec3 uEye;
layout(location = 4) uniform vec2 uViewport;
layout(binding = 0) uniform sampler2D uCutaway;
layout(binding = 1) uniform sampler2D uCutawayDilated;
out vec4 outColor;
void main() {
  if (uCut != 0) {
    vec2 uv = gl_FragCoord.xy / uViewport;
    float cut = gl_FrontFacing ? texture(uCutaway, uv).r : texture(uCutawayDilated, uv).r;
    if (gl_FragCoord.z < cut) discard;
  }
  vec3 n = normalize(cross(dFdx(vPosition), dFdy(vPosition)));
  float light = abs(dot(n, normalize(uEye - vPosition)));
  outColor = vec4(uColor * (0.25 + 0.75 * light) * (gl_FrontFacing ? 1.0 : 0.6), 1.0);
})";

GLuint compile(GLenum stage, const char* source) {
  const GLuint shader = glCreateShader(stage);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    throw cutaway::Error(std::string("own-gl shader: ") + log);
  }
  return shader;
}

GLuint program() {
  const GLuint p = glCreateProgram();
  glAttachShader(p, compile(GL_VERTEX_SHADER, kVertex));
  glAttachShader(p, compile(GL_FRAGMENT_SHADER, kFragment));
  glLinkProgram(p);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetProgramInfoLog(p, sizeof log, nullptr, log);
    throw cutaway::Error(std::string("own-gl program: ") + log);
  }
  return p;
}

struct Mesh {
  GLuint vertexArray = 0;
  GLsizei count = 0;
  void draw() const {
    glBindVertexArray(vertexArray);
    glDrawArrays(GL_TRIANGLES, 0, count);
  }
};

Mesh upload(const std::vector<glm::vec3>& triangles) {
  Mesh m;
  m.count = GLsizei(triangles.size());
  GLuint buffer = 0;
  glCreateBuffers(1, &buffer);
  glNamedBufferStorage(buffer, GLsizeiptr(triangles.size() * sizeof(glm::vec3)), triangles.data(), 0);
  glCreateVertexArrays(1, &m.vertexArray);
  glVertexArrayVertexBuffer(m.vertexArray, 0, buffer, 0, sizeof(glm::vec3));
  glEnableVertexArrayAttrib(m.vertexArray, 0);
  glVertexArrayAttribFormat(m.vertexArray, 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(m.vertexArray, 0, 0);
  return m;
}

// Counter-clockwise seen from outside, for shapes around the origin (front faces outside).
std::vector<glm::vec3> outward(std::vector<glm::vec3> t) {
  for (std::size_t i = 0; i + 2 < t.size(); i += 3)
    if (glm::dot(glm::cross(t[i + 1] - t[i], t[i + 2] - t[i]), t[i] + t[i + 1] + t[i + 2]) < 0.0f)
      std::swap(t[i + 1], t[i + 2]);
  return t;
}

// A latitude-longitude sphere and an axis-aligned box, as triangle lists.
std::vector<glm::vec3> sphere(float radius, int rings, int segments) {
  const auto point = [&](int ring, int segment) {
    const float theta = glm::pi<float>() * float(ring) / float(rings);
    const float phi = 2.0f * glm::pi<float>() * float(segment) / float(segments);
    return radius * glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                              std::sin(theta) * std::sin(phi));
  };
  std::vector<glm::vec3> t;
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const glm::vec3 a = point(r, s), b = point(r + 1, s), c = point(r + 1, s + 1),
                      d = point(r, s + 1);
      t.insert(t.end(), {a, b, c, a, c, d});
    }
  return t;
}

std::vector<glm::vec3> box(float half) {
  std::vector<glm::vec3> t;
  for (int axis = 0; axis < 3; ++axis)
    for (const float side : {-half, half}) {
      glm::vec3 corner[4];
      for (int i = 0; i < 4; ++i) {
        glm::vec3 p(0.0f);
        p[axis] = side;
        p[(axis + 1) % 3] = (i == 1 || i == 2) ? half : -half;
        p[(axis + 2) % 3] = (i >= 2) ? half : -half;
        corner[i] = p;
      }
      t.insert(t.end(), {corner[0], corner[1], corner[2], corner[0], corner[2], corner[3]});
    }
  return t;
}

GLuint texture(GLenum format) {
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &id);
  glTextureStorage2D(id, 1, format, kWidth, kHeight);
  return id;
}

GLuint framebuffer(GLuint color, GLuint depth) {
  GLuint id = 0;
  glCreateFramebuffers(1, &id);
  if (color) glNamedFramebufferTexture(id, GL_COLOR_ATTACHMENT0, color, 0);
  else glNamedFramebufferDrawBuffer(id, GL_NONE);
  glNamedFramebufferTexture(id, GL_DEPTH_ATTACHMENT, depth, 0);
  return id;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT.png\n", argv[0]);
    return 2;
  }
  try {
    auto context = cutaway::gl::HeadlessContext::create();  // or the application's window
    const GLuint shading = program();
    const Mesh ball = upload(outward(sphere(0.6f, 24, 48))), shell = upload(outward(box(1.2f)));
    const glm::vec3 eye(3.0f, 2.4f, 4.0f);
    const glm::mat4 projection =
        glm::perspective(glm::radians(40.0f), float(kWidth) / kHeight, 1.0f, 20.0f);
    const glm::mat4 view = glm::lookAt(eye, glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    const glm::mat4 viewProjection = projection * view;
    glUseProgram(shading);
    glProgramUniformMatrix4fv(shading, 0, 1, GL_FALSE, &viewProjection[0][0]);
    glProgramUniform3fv(shading, 3, 1, &eye[0]);
    glProgramUniform2f(shading, 4, float(kWidth), float(kHeight));
    glViewport(0, 0, kWidth, kHeight);
    glEnable(GL_DEPTH_TEST);

    // 1. The ball's rear hull: its farthest depth, cleared to 0 (Burns08 §5.1).
    const GLuint interestDepth = texture(GL_DEPTH_COMPONENT32F);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer(0, interestDepth));
    glClearDepth(0.0);
    glClear(GL_DEPTH_BUFFER_BIT);
    glDepthFunc(GL_GREATER);
    glProgramUniform1i(shading, 2, 0);
    ball.draw();

    // 2. The library's cutaway surface from it.
    cutaway::AdaptiveCutawaySurface surface({.angle = 35.0f, .bufferSize = 512});
    const GLuint cut = surface.compute(interestDepth, projection, view);

    // 3. The application's picture: the ball, and the box clipped by the surface.
    const GLuint color = texture(GL_RGBA8), depth = texture(GL_DEPTH_COMPONENT32F);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer(color, depth));
    glClearColor(1.0f, 1.0f, 1.0f, 1.0f);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glDepthFunc(GL_LESS);
    glProgramUniform3f(shading, 1, 0.85f, 0.2f, 0.15f);
    ball.draw();
    glBindTextureUnit(0, cut);
    glBindTextureUnit(1, surface.dilatedTexture());
    glProgramUniform1i(shading, 2, 1);
    glProgramUniform3f(shading, 1, 0.7f, 0.7f, 0.75f);
    shell.draw();

    cutaway::Rgba8Image image(kWidth, kHeight);
    glGetTextureImage(color, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(image.pixels.size()),
                      image.pixels.data());
    image.flipVertically();
    cutaway::writePng(argv[1], image);
  } catch (const cutaway::Error& e) {
    std::fprintf(stderr, "own-gl: %s\n", e.what());
    return 1;
  }
  return 0;
}
