// The adaptive cutaway surface for another application's OpenGL (AdaptiveCutawaySurface):
// fed the renderer's own seed, it returns the renderer's cutaway depth on both compute paths;
// fed a seed at screen resolution, it pools the farthest depth per buffer texel and grows the
// same surface as the CPU reference (fields::jumpFlooding); it keeps the application's GL
// state and refuses options out of range.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "cutaway/core/error.hpp"
#include "cutaway/cutters/adaptive_surface.hpp"
#include "cutaway/render/renderer.hpp"
#include "gl_test_context.hpp"
#include "mismatches.hpp"
#include "render_aovs.hpp"

using namespace cutaway;
using test::aov;
using test::renderAovs;

namespace {

const std::string kData = CUTAWAY_TEST_DATA;

// An R32F (or depth) texture of `texels`, rows bottom to top.
gl::Texture texture(int width, int height, const std::vector<float>& texels,
                    GLenum format = GL_R32F) {
  gl::Texture t = gl::Texture::create2D(format, width, height);
  glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureSubImage2D(t.id(), 0, 0, 0, width, height,
                      format == GL_R32F ? GL_RED : GL_DEPTH_COMPONENT, GL_FLOAT, texels.data());
  return t;
}

std::vector<float> readTexture(GLuint id, int n) {
  std::vector<float> texels(std::size_t(n) * n);
  glGetTextureImage(id, 0, GL_RED, GL_FLOAT, GLsizei(texels.size() * sizeof(float)), texels.data());
  return texels;
}

// An AOV (rows top-down) as OpenGL stores it (rows bottom-up).
std::vector<float> bottomUp(const FloatImage& image) {
  std::vector<float> out(std::size_t(image.width) * image.height);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      out[std::size_t(y) * image.width + x] = image.at(x, image.height - 1 - y)[0];
  return out;
}

const char* kBoxes = R"({"resolution": [96, 64], "samples": 1, "style": {"name": "gooch", "lines": false},
  "camera": {"eye": [2, 5, 14], "target": [0, 0, 0], "fov": 45, "near": 4, "far": 30},
  "cutters": {"adaptive": {"angle": 40, "bufferSize": 64, "directionalConstraint": true}},
  "objects": [{"name": "wall", "file": "render/plane.obj", "transform": {"translate": [0, 0, -4]}}],
  "proxies": [{"name": "a", "box": {"min": [-2, -1, -1], "max": [-1, 0.5, 0.5]}, "params": {"cutawayAngle": 25}},
              {"name": "b", "box": {"min": [0.5, -0.5, 0], "max": [2, 1, 1.5]}, "params": {"cutawayAngle": 55}}]})";

}  // namespace

class SurfaceAsTheRenderer
    : public ::testing::TestWithParam<AdaptiveCutawayOptions::Compute> {};

// The renderer's seed in, the renderer's cutaway depth out.
TEST_P(SurfaceAsTheRenderer, GivesTheRenderersCutawayDepth) {
  Scene scene = parseScene(kBoxes, "boxes.json", kData);
  AdaptiveCutawayOptions& options = *scene.cutters.find<AdaptiveCutawayOptions>();
  options.compute = GetParam();
  std::vector<Aov> aovs;
  {
    Renderer renderer(scene, test::glContext().info());
    renderer.render();
    aovs = renderer.readAovs();
  }
  const int n = options.bufferSize;
  const gl::Texture seed = texture(n, n, bottomUp(aov(aovs, "seedDepth")));
  const gl::Texture angle = texture(n, n, bottomUp(aov(aovs, "seedAngle")));
  const Camera camera = scene.resolvedCamera();
  AdaptiveCutawaySurface surface(options);
  EXPECT_STREQ(surface.computePath(),
               options.compute == AdaptiveCutawayOptions::Compute::Gpu ? "gpu" : "cpu");
  const GLuint cut = surface.compute(seed.id(), camera.projectionMatrix(96.0f / 64.0f),
                                     camera.view(), angle.id());
  EXPECT_EQ(cut, surface.cutawayTexture());
  EXPECT_EQ(readTexture(cut, n), bottomUp(aov(aovs, "cutawayDepth")));
  EXPECT_EQ(readTexture(surface.dilatedTexture(), n), bottomUp(aov(aovs, "cutawayDilated")));
  int seeded = 0;
  for (float s : readTexture(surface.seedTexture(), n)) seeded += s > 0.0f;
  EXPECT_GT(seeded, 50);
}

INSTANTIATE_TEST_SUITE_P(BothPaths, SurfaceAsTheRenderer,
                         ::testing::Values(AdaptiveCutawayOptions::Compute::Gpu,
                                           AdaptiveCutawayOptions::Compute::Cpu));

namespace {

// Random discs of interest at depths in [0.6, 0.95], each with its own angle θ.
struct InterestImage {
  int width, height;
  std::vector<float> depth, angle;  // rows bottom to top; depth 0: none
};

InterestImage randomDiscs(int width, int height, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  InterestImage image{width, height, std::vector<float>(std::size_t(width) * height, 0.0f),
                      std::vector<float>(std::size_t(width) * height, 0.3f)};
  for (int disc = 0; disc < 6; ++disc) {
    const float cx = u(rng) * float(width), cy = u(rng) * float(height);
    const float r = (0.02f + 0.08f * u(rng)) * float(width), theta = 0.2f + 1.0f * u(rng);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const std::size_t i = std::size_t(y) * width + x;
        const float z = 0.6f + 0.35f * u(rng);
        if (std::hypot(float(x) + 0.5f - cx, float(y) + 0.5f - cy) < r && z > image.depth[i])
          image.depth[i] = z, image.angle[i] = theta;
      }
  }
  return image;
}

// The seed seed_import.frag documents: each n×n texel p takes the farthest depth over the
// source texels [p·S/n, max((p+1)·S/n, p·S/n + 1)) on each axis (the first in row order on
// ties), and the angle there.
std::pair<std::vector<float>, std::vector<float>> pooled(const InterestImage& image, int n) {
  std::vector<float> depth(std::size_t(n) * n), angle(std::size_t(n) * n);
  for (int py = 0; py < n; ++py)
    for (int px = 0; px < n; ++px) {
      const int x0 = px * image.width / n, y0 = py * image.height / n;
      const int x1 = std::max((px + 1) * image.width / n, x0 + 1);
      const int y1 = std::max((py + 1) * image.height / n, y0 + 1);
      float best = 0.0f;
      std::size_t at = std::size_t(y0) * image.width + x0;
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
          const std::size_t i = std::size_t(y) * image.width + x;
          if (image.depth[i] > best) best = image.depth[i], at = i;
        }
      depth[std::size_t(py) * n + px] = best;
      angle[std::size_t(py) * n + px] = image.angle[at];
    }
  return {depth, angle};
}

struct PoolCase {
  int width, height, n;
};

}  // namespace

class SurfaceFromAScreen : public ::testing::TestWithParam<PoolCase> {};

// A screen-sized depth of the objects of interest (and their angles) in: the seed is its
// pooling, the surface the CPU reference's on that seed, on both paths; with footprints of
// several texels (5n × 3n), and of one or none (640 × 480 into 512²).
TEST_P(SurfaceFromAScreen, PoolsTheDepthAndGrowsTheReferenceSurface) {
  test::glContext();
  const auto [w, h, n] = GetParam();
  const InterestImage image = randomDiscs(w, h, unsigned(w + n));
  const auto [seedDepth, seedAngle] = pooled(image, n);
  const gl::Texture depth = texture(w, h, image.depth, GL_DEPTH_COMPONENT32F);
  const gl::Texture angle = texture(w, h, image.angle);
  const glm::mat4 projection =
      glm::perspective(glm::radians(50.0f), float(w) / float(h), 1.0f, 20.0f);
  const glm::mat4 view = glm::lookAt(glm::vec3(1, 3, 8), glm::vec3(0), glm::vec3(0, 1, 0));
  AdaptiveCutawaySurface gpu({.bufferSize = n, .compute = AdaptiveCutawayOptions::Compute::Gpu});
  AdaptiveCutawaySurface cpu({.bufferSize = n, .compute = AdaptiveCutawayOptions::Compute::Cpu});
  const std::vector<float> gpuCut =
      readTexture(gpu.compute(depth.id(), projection, view, angle.id()), n);
  const std::vector<float> cpuCut =
      readTexture(cpu.compute(depth.id(), projection, view, angle.id()), n);
  EXPECT_EQ(readTexture(gpu.seedTexture(), n), seedDepth);

  const AdaptiveCutawayOptions defaults;
  const fields::CutawayField reference = fields::jumpFlooding(
      makeSeedImage(seedDepth, seedAngle, n, defaults, {projection, glm::mat3(view), false}),
      -1.0f, defaults.variant);
  int cut = 0;
  test::Mismatches cpuWrong, gpuWrong;  // window depths
  for (std::size_t i = 0; i < seedDepth.size(); ++i) {
    const float expected = reference.depth[i] * 0.5f + 0.5f;
    const int x = int(i % std::size_t(n)), y = int(i / std::size_t(n));
    if (cpuCut[i] != expected) cpuWrong.add(x, y, expected, cpuCut[i]);
    if (std::abs(gpuCut[i] - expected) > 2e-6f) gpuWrong.add(x, y, expected, gpuCut[i]);
    cut += expected > 0.0f;
  }
  EXPECT_EQ(cpuWrong.count(), 0) << "CPU path: " << cpuWrong;
  EXPECT_EQ(gpuWrong.count(), 0) << "GPU path: " << gpuWrong;
  EXPECT_GT(cut, n * n / 10);
}

INSTANTIATE_TEST_SUITE_P(Sizes, SurfaceFromAScreen,
                         ::testing::Values(PoolCase{160, 96, 32}, PoolCase{640, 480, 512}),
                         [](const ::testing::TestParamInfo<PoolCase>& info) {
                           return std::to_string(info.param.width) + "x" +
                                  std::to_string(info.param.height) + "_into_" +
                                  std::to_string(info.param.n);
                         });

// The application's framebuffers, program, vertex array, viewport, switches, colour mask and
// pixel-transfer state come back as they were, and none of them changes the result.
TEST(AdaptiveCutawaySurface, KeepsTheApplicationsStateAndIsNotDisturbedByIt) {
  test::glContext();
  const InterestImage image = randomDiscs(64, 64, 3);
  const gl::Texture depth = texture(64, 64, image.depth);
  const glm::mat4 projection = glm::ortho(-1.0f, 1.0f, -1.0f, 1.0f, 0.1f, 10.0f);
  AdaptiveCutawaySurface surface({.bufferSize = 32});
  const std::vector<float> clean = readTexture(surface.compute(depth.id(), projection, glm::mat4(1.0f)), 32);

  gl::Texture color = gl::Texture::create2D(GL_RGBA8, 8, 8);
  gl::Framebuffer draw = gl::Framebuffer::create(), read = gl::Framebuffer::create();
  glNamedFramebufferTexture(draw.id(), GL_COLOR_ATTACHMENT0, color.id(), 0);
  glNamedFramebufferTexture(read.id(), GL_COLOR_ATTACHMENT0, color.id(), 0);
  const gl::VertexArray vertexArray = gl::VertexArray::create();
  const gl::Buffer pixels = gl::Buffer::create(64, nullptr, GL_DYNAMIC_STORAGE_BIT);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, draw.id());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, read.id());
  glBindVertexArray(vertexArray.id());
  glBindBuffer(GL_PIXEL_PACK_BUFFER, pixels.id());
  glViewport(1, 2, 3, 4);
  for (const GLenum on : {GL_DEPTH_TEST, GL_BLEND, GL_SCISSOR_TEST, GL_CULL_FACE}) glEnable(on);
  glBlendFunc(GL_ONE, GL_ONE);
  glScissor(0, 0, 1, 1);
  glCullFace(GL_FRONT_AND_BACK);
  glColorMask(GL_FALSE, GL_TRUE, GL_FALSE, GL_TRUE);
  glPixelStorei(GL_PACK_ALIGNMENT, 8);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 7);
  const GLuint cut = surface.compute(depth.id(), projection, glm::mat4(1.0f));

  GLint value = 0, viewport[4];
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &value);
  EXPECT_EQ(GLuint(value), draw.id());
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &value);
  EXPECT_EQ(GLuint(value), read.id());
  glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &value);
  EXPECT_EQ(GLuint(value), vertexArray.id());
  glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &value);
  EXPECT_EQ(GLuint(value), pixels.id());
  glGetIntegerv(GL_VIEWPORT, viewport);
  EXPECT_EQ(std::vector<GLint>(viewport, viewport + 4), (std::vector<GLint>{1, 2, 3, 4}));
  for (const GLenum on : {GL_DEPTH_TEST, GL_BLEND, GL_SCISSOR_TEST, GL_CULL_FACE})
    EXPECT_TRUE(glIsEnabled(on)) << on;
  GLboolean mask[4];
  glGetBooleanv(GL_COLOR_WRITEMASK, mask);
  EXPECT_EQ(mask[0], GL_FALSE);
  EXPECT_EQ(mask[1], GL_TRUE);
  glGetIntegerv(GL_PACK_ALIGNMENT, &value);
  EXPECT_EQ(value, 8);
  glGetIntegerv(GL_UNPACK_ROW_LENGTH, &value);
  EXPECT_EQ(value, 7);

  // Back to OpenGL's defaults before reading the result.
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  for (const GLenum on : {GL_DEPTH_TEST, GL_BLEND, GL_SCISSOR_TEST, GL_CULL_FACE}) glDisable(on);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glBindVertexArray(0);
  EXPECT_EQ(readTexture(cut, 32), clean);
}

TEST(AdaptiveCutawaySurface, RefusesOptionsOutOfRange) {
  test::glContext();
  try {
    AdaptiveCutawaySurface surface({.angle = 120.0f});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.place(), "angle");
    EXPECT_NE(e.reason().find("outside [0, 90]"), std::string::npos) << e.what();
  }
  EXPECT_THROW(AdaptiveCutawaySurface({.bufferSize = 0}), Error);
  AdaptiveCutawaySurface surface({.bufferSize = 16});
  surface.options().edgeRegion = -1.0f;
  const gl::Texture none = texture(16, 16, std::vector<float>(256, 0.0f));
  EXPECT_THROW(surface.compute(none.id(), glm::mat4(1.0f), glm::mat4(1.0f)), Error);
}
