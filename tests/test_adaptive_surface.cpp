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

// A 5n×3n depth texture of random discs: the seed is its per-texel maximum, the surface the
// CPU reference's on that seed; with the default uniform angle.
TEST(AdaptiveCutawaySurface, PoolsAScreenSizedDepthAndGrowsTheReferenceSurface) {
  test::glContext();
  constexpr int n = 32, w = 5 * n, h = 3 * n;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<float> depth(std::size_t(w) * h, 0.0f);
  for (int disc = 0; disc < 6; ++disc) {
    const float cx = u(rng) * w, cy = u(rng) * h, r = 2.0f + 12.0f * u(rng);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        if (std::hypot(x + 0.5f - cx, y + 0.5f - cy) < r)
          depth[std::size_t(y) * w + x] =
              std::max(depth[std::size_t(y) * w + x], 0.6f + 0.35f * u(rng));
  }
  std::vector<float> pooled(std::size_t(n) * n, 0.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float& p = pooled[std::size_t(y * n / h) * n + x * n / w];
      p = std::max(p, depth[std::size_t(y) * w + x]);
    }
  const gl::Texture input = texture(w, h, depth, GL_DEPTH_COMPONENT32F);
  const glm::mat4 projection = glm::perspective(glm::radians(50.0f), 5.0f / 3.0f, 1.0f, 20.0f);
  const glm::mat4 view = glm::lookAt(glm::vec3(1, 3, 8), glm::vec3(0), glm::vec3(0, 1, 0));
  AdaptiveCutawaySurface gpu({.bufferSize = n, .compute = AdaptiveCutawayOptions::Compute::Gpu});
  AdaptiveCutawaySurface cpu({.bufferSize = n, .compute = AdaptiveCutawayOptions::Compute::Cpu});
  const std::vector<float> gpuCut = readTexture(gpu.compute(input.id(), projection, view), n);
  const std::vector<float> cpuCut = readTexture(cpu.compute(input.id(), projection, view), n);
  EXPECT_EQ(readTexture(gpu.seedTexture(), n), pooled);

  const AdaptiveCutawayOptions defaults;
  const std::vector<float> angles(pooled.size(), glm::radians(defaults.angle));
  fields::CutawayField reference = fields::jumpFlooding(
      makeSeedImage(pooled, angles, n, defaults, {projection, glm::mat3(view), false}), -1.0f,
      defaults.variant);
  int cut = 0;
  for (std::size_t i = 0; i < pooled.size(); ++i) {
    const float expected = reference.depth[i] * 0.5f + 0.5f;
    EXPECT_EQ(cpuCut[i], expected) << "texel " << i;
    EXPECT_NEAR(gpuCut[i], expected, 2e-6f) << "texel " << i;
    cut += expected > 0.0f;
  }
  EXPECT_GT(cut, 200);
}

TEST(AdaptiveCutawaySurface, KeepsTheApplicationsState) {
  test::glContext();
  gl::Texture color = gl::Texture::create2D(GL_RGBA8, 8, 8);
  gl::Framebuffer fb = gl::Framebuffer::create();
  glNamedFramebufferTexture(fb.id(), GL_COLOR_ATTACHMENT0, color.id(), 0);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fb.id());
  glViewport(1, 2, 3, 4);
  glEnable(GL_DEPTH_TEST);
  AdaptiveCutawaySurface surface({.bufferSize = 16});
  const gl::Texture none = texture(16, 16, std::vector<float>(256, 0.0f));
  surface.compute(none.id(), glm::ortho(-1.0f, 1.0f, -1.0f, 1.0f, 0.1f, 10.0f), glm::mat4(1.0f));
  GLint framebuffer = 0, viewport[4];
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
  glGetIntegerv(GL_VIEWPORT, viewport);
  EXPECT_EQ(GLuint(framebuffer), fb.id());
  EXPECT_EQ(viewport[0], 1);
  EXPECT_EQ(viewport[3], 4);
  EXPECT_TRUE(glIsEnabled(GL_DEPTH_TEST));
  // Without seeds nothing is cut.
  for (float c : readTexture(surface.cutawayTexture(), 16)) EXPECT_EQ(c, 0.0f);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glDisable(GL_DEPTH_TEST);
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
