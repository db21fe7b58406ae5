// GPU tests of the frame and the renderer: AOV values against the camera, frame validation,
// timer queries against the wall clock, the device's limits on render targets.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <type_traits>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "cutaway/core/error.hpp"
#include "cutaway/geometry/pipe_network.hpp"
#include "cutaway/io/raster_terrain.hpp"
#include "cutaway/render/renderer.hpp"
#include "expect_error.hpp"
#include "frame/fullscreen.hpp"
#include "frame/scene_meshes.hpp"
#include "gl_test_context.hpp"
#include "golden.hpp"
#include "run_command.hpp"

using namespace cutaway;

// A renderer refers to its scene, so it takes no temporary one (it would dangle by the first
// frame: the first frame read a freed transfer function).
static_assert(std::is_constructible_v<Renderer, const Scene&, const gl::ContextInfo&>);
static_assert(!std::is_constructible_v<Renderer, Scene, const gl::ContextInfo&>);
static_assert(!std::is_constructible_v<Renderer, Scene&&, const gl::ContextInfo&>);

namespace {

const std::string kData = CUTAWAY_TEST_DATA;

Scene planeScene(int samples, const std::string& cameraJson) {
  return parseScene(R"({"resolution": [64, 48], "samples": )" + std::to_string(samples) +
                        R"(, "style": {"name": "blinn-phong", "lines": false},
      "objects": [{"name": "plane", "file": "render/plane.obj",
                   "transform": {"rotate": {"axis": [1, 0, 0], "degrees": -35}}}],
      "camera": )" + cameraJson +
                        "}",
                    "plane.json", kData);
}

const Aov& find(const std::vector<Aov>& aovs, const std::string& name) {
  for (const auto& a : aovs)
    if (a.name == name) return a;
  throw std::runtime_error("no AOV " + name);
}

// Where the driver puts sample 0 of a multisample target, in pixel units (y up).
glm::vec2 firstSamplePosition(int samples) {
  if (samples == 1) return glm::vec2(0.5f);  // the frame's one-sample targets are 2-D textures
  gl::Texture texture = gl::Texture::create2D(GL_RGBA8, 4, 4, samples);
  gl::Framebuffer framebuffer = gl::Framebuffer::create();
  glNamedFramebufferTexture(framebuffer.id(), GL_COLOR_ATTACHMENT0, texture.id(), 0);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
  glm::vec2 position(0.5f);
  glGetMultisamplefv(GL_SAMPLE_POSITION, 0, &position[0]);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return position;
}

// The plane's world-space intersection with the ray through `offset` within pixel (x, y)
// (rows top to bottom, offset y up), computed on the CPU from the camera alone.
std::optional<glm::vec3> rayHit(const Scene& scene, const Camera& c, int x, int y,
                                glm::vec2 offset = glm::vec2(0.5f)) {
  const float aspect = float(scene.width) / float(scene.height);
  const glm::mat4 inverse = glm::inverse(c.projectionMatrix(aspect) * c.view());
  const glm::vec2 ndc((x + offset.x) / scene.width * 2.0f - 1.0f,
                      (scene.height - 1 - y + offset.y) / scene.height * 2.0f - 1.0f);
  glm::vec4 a = inverse * glm::vec4(ndc, -1.0f, 1.0f), b = inverse * glm::vec4(ndc, 1.0f, 1.0f);
  const glm::vec3 origin = glm::vec3(a) / a.w, end = glm::vec3(b) / b.w;
  const glm::mat4 model = scene.objects[0].transform;
  const glm::vec3 n = glm::normalize(glm::vec3(model * glm::vec4(0, 0, 1, 0)));
  const glm::vec3 d = end - origin;
  const float t = glm::dot(glm::vec3(model[3]) - origin, n) / glm::dot(d, n);
  const glm::vec3 hit = origin + t * d;
  const glm::vec3 local = glm::vec3(glm::inverse(model) * glm::vec4(hit, 1.0f));
  if (std::abs(local.x) > 9.9f || std::abs(local.y) > 9.9f) return std::nullopt;
  return hit;
}

}  // namespace

std::string planeAovTestName(const ::testing::TestParamInfo<std::tuple<int, std::string>>& info) {
  const int samples = std::get<0>(info.param);
  const bool ortho = std::get<1>(info.param).find("orthographic") != std::string::npos;
  return std::string(ortho ? "orthographic_" : "perspective_") + std::to_string(samples) +
         "samples";
}

class PlaneAovTest : public ::testing::TestWithParam<std::tuple<int, std::string>> {};

// Every pixel of the AOVs against the analytic ray–plane intersection.
TEST_P(PlaneAovTest, AovsMatchTheCamera) {
  test::glContext();
  const auto& [samples, cameraJson] = GetParam();
  const Scene scene = planeScene(samples, cameraJson);
  Renderer renderer(scene, test::glContext().info());
  const Camera camera = scene.resolvedCamera();
  renderer.render(camera);
  const auto aovs = renderer.readAovs();
  const FloatImage& viewDepth = find(aovs, "viewDepth").image;
  const FloatImage& depth = find(aovs, "depth").image;
  const FloatImage& position = find(aovs, "position").image;
  const FloatImage& objectId = find(aovs, "objectId").image;
  const float aspect = float(scene.width) / float(scene.height);
  const glm::mat4 viewProjection = camera.projectionMatrix(aspect) * camera.view();
  const glm::vec2 sample0 = firstSamplePosition(scene.samples);
  int checked = 0;
  for (int y = 0; y < scene.height; ++y)
    for (int x = 0; x < scene.width; ++x) {
      const auto hit = rayHit(scene, camera, x, y);
      if (!hit) continue;
      ++checked;
      const glm::vec3 eyeSpace = glm::vec3(camera.view() * glm::vec4(*hit, 1.0f));
      // Depth is per sample: evaluate it where sample 0 lies, not at the pixel centre.
      const auto sampleHit = rayHit(scene, camera, x, y, sample0);
      if (!sampleHit) continue;
      const glm::vec4 clip = viewProjection * glm::vec4(*sampleHit, 1.0f);
      const float windowDepth = 0.5f * clip.z / clip.w + 0.5f;
      ASSERT_EQ(objectId.at(x, y)[0], 0.0f) << x << "," << y;
      ASSERT_NEAR(viewDepth.at(x, y)[0], -eyeSpace.z, 1e-4f * camera.far) << x << "," << y;
      ASSERT_NEAR(depth.at(x, y)[0], windowDepth, 1e-5f) << x << "," << y;
      for (int i = 0; i < 3; ++i)
        ASSERT_NEAR(position.at(x, y)[i], (*hit)[i], 1e-3f) << x << "," << y;
    }
  EXPECT_GT(checked, scene.width * scene.height / 4);
}

INSTANTIATE_TEST_SUITE_P(
    Cameras, PlaneAovTest,
    ::testing::Combine(
        ::testing::Values(1, 4),
        ::testing::Values(
            R"({"eye": [0, 2, 12], "target": [0, 0, 0], "fov": 50, "near": 2, "far": 30})",
            R"({"projection": "orthographic", "eye": [1, 3, 12], "target": [0, 0, 0],
                              "height": 12, "near": 1, "far": 40})")),
    planeAovTestName);

// The AOVs are resolved when read, with the reading renderer's camera: another renderer that
// drew in between (binding its own frame uniforms) changes nothing.
TEST(Renderer, AovsReadAfterAnotherRendererDrewAreItsOwn) {
  const Scene a = planeScene(4, R"({"eye": [0, 2, 12], "target": [0, 0, 0], "fov": 50})");
  const Scene b = planeScene(4, R"({"eye": [5, 9, 4], "target": [0, 0, 0], "fov": 30})");
  Renderer first(a, test::glContext().info()), second(b, test::glContext().info());
  first.render(a.resolvedCamera());
  const auto alone = first.readAovs();
  first.render(a.resolvedCamera());
  second.render(b.resolvedCamera());
  const auto after = first.readAovs();
  for (const char* name : {"position", "viewDepth", "normal", "objectId", "depth"}) {
    const FloatImage &x = find(alone, name).image, &y = find(after, name).image;
    ASSERT_EQ(x.data, y.data) << name;
  }
}

TEST(Renderer, BackgroundAovsAreMarked) {
  const Scene scene = planeScene(4, R"({"eye": [0, 0, 30], "target": [0, 0, 0], "fov": 60})");
  Renderer renderer(scene, test::glContext().info());
  renderer.render();
  const auto aovs = renderer.readAovs();
  // The top-left corner sees past the plane's edge.
  EXPECT_EQ(find(aovs, "objectId").image.at(0, 0)[0], -1.0f);
  EXPECT_EQ(find(aovs, "viewDepth").image.at(0, 0)[0], 0.0f);
  EXPECT_EQ(find(aovs, "depth").image.at(0, 0)[0], 1.0f);
  EXPECT_EQ(find(aovs, "objectId").image.at(32, 24)[0], 0.0f);
}

// Underground views: a camera below a terrain-like plane (it faces +z, tilted; the camera looks
// at its underside) sees it, drawn two-sided with its normal turned to the viewer, not culled.
TEST(Renderer, ACameraBelowTheGroundSeesItsUnderside) {
  const Scene scene = planeScene(4, R"({"eye": [0, 0, -5], "target": [0, 0, 0], "fov": 60})");
  Renderer renderer(scene, test::glContext().info());
  renderer.render();
  const auto aovs = renderer.readAovs();
  const FloatImage& id = find(aovs, "objectId").image;
  const FloatImage& normal = find(aovs, "normal").image;
  for (int y = 0; y < id.height; ++y)
    for (int x = 0; x < id.width; ++x) {
      ASSERT_EQ(id.at(x, y)[0], 0.0f) << x << "," << y;
      ASSERT_NEAR(normal.at(x, y)[2], -std::cos(glm::radians(35.0f)), 1e-3f)  // towards the camera
          << x << "," << y;
    }
}

// A mirroring transform (negative determinant) turns the triangles' winding on screen; the
// object must still show its outside: every pixel of a cube mirrored in x has a normal facing
// the eye (drawn as a front face: two-sided shading turns the normal of a back face), as the
// same cube unmirrored, and covers the same pixels.
TEST(Renderer, AMirroredObjectShowsItsOutside) {
  int covered[2] = {};
  for (const bool mirrored : {false, true}) {
    SCOPED_TRACE(mirrored);
    const Scene scene = parseScene(
        std::string(R"({"resolution": [64, 48], "samples": 1,
        "style": {"name": "blinn-phong", "lines": false},
        "camera": {"eye": [2.2, 1.7, 3.0], "target": [0, 0, 0], "fov": 45},
        "objects": [{"name": "cube", "file": "meshes/cube.obj", "color": [0.8, 0.3, 0.2],
                     "transform": {"translate": )") +
            (mirrored ? "[0.5, -0.5, -0.5], \"scale\": [-1, 1, 1]" : "[-0.5, -0.5, -0.5]") + "}}]}",
        "mirror.json", kData);
    Renderer renderer(scene, test::glContext().info());
    renderer.render();
    const auto aovs = renderer.readAovs();
    const FloatImage &id = find(aovs, "objectId").image, &normal = find(aovs, "normal").image,
                     &position = find(aovs, "position").image;
    const glm::vec3 eye(2.2f, 1.7f, 3.0f);
    int& pixels = covered[mirrored];
    for (int y = 0; y < id.height; ++y)
      for (int x = 0; x < id.width; ++x) {
        if (id.at(x, y)[0] < 0.0f) continue;
        ++pixels;
        const glm::vec3 n(normal.at(x, y)[0], normal.at(x, y)[1], normal.at(x, y)[2]);
        const glm::vec3 p(position.at(x, y)[0], position.at(x, y)[1], position.at(x, y)[2]);
        ASSERT_GT(glm::dot(n, eye - p), 0.0f) << x << "," << y;
      }
    EXPECT_GT(pixels, 250);
  }
  EXPECT_EQ(covered[0], covered[1]);
}

// The object parameter doubleSided: false (glTF's doubleSided) culls the back faces of an
// object no cutter cuts: the plane is seen from above, and not at all from below.
// A cube scaled far from 1 (fitted, so it looks the same) is shaded, not black: its normals
// are the unit cube's. At 1e12 they came out too short for the vanishing-normal test, at 1e14
// the 4×4 inverse's determinant overflowed to zero normals.
TEST(Renderer, ObjectsScaledFarFromOneKeepTheirNormals) {
  std::vector<std::vector<float>> normals;
  for (const char* scale : {"1", "1e-6", "1e12", "1e14"}) {
    SCOPED_TRACE(scale);
    const Scene scene = parseScene(std::string(R"({"resolution": [64, 48], "samples": 1,
        "style": {"name": "gooch", "lines": false},
        "camera": {"fit": true, "eye": [2.2, 1.7, 3.0], "target": [0, 0, 0], "fov": 45},
        "objects": [{"name": "cube", "file": "meshes/cube.obj", "transform": {"scale": )") +
                                       scale + "}}]}",
                                   "scaled.json", kData);
    Renderer renderer(scene, test::glContext().info());
    renderer.render();
    const auto aovs = renderer.readAovs();
    const FloatImage &id = find(aovs, "objectId").image, &normal = find(aovs, "normal").image;
    int pixels = 0;
    for (int y = 0; y < id.height; ++y)
      for (int x = 0; x < id.width; ++x) {
        if (id.at(x, y)[0] < 0.0f) continue;
        ++pixels;
        const glm::vec3 n(normal.at(x, y)[0], normal.at(x, y)[1], normal.at(x, y)[2]);
        ASSERT_NEAR(glm::length(n), 1.0f, 1e-3f) << x << "," << y;
      }
    EXPECT_GT(pixels, 250);
    normals.push_back(normal.data);
  }
  for (std::size_t i = 1; i < normals.size(); ++i) {
    ASSERT_EQ(normals[i].size(), normals[0].size());
    int differ = 0;
    for (std::size_t k = 0; k < normals[0].size(); ++k)
      differ += std::abs(normals[i][k] - normals[0][k]) > 1e-3f;
    EXPECT_LE(differ, 3 * 8) << i;  // edge pixels may fall either way
  }
}

TEST(Renderer, ASingleSidedObjectIsCulledFromBehind) {
  for (const float eyeZ : {5.0f, -5.0f}) {
    SCOPED_TRACE(eyeZ);
    const Scene scene = parseScene(
        R"({"resolution": [64, 48], "samples": 4, "style": {"name": "gooch", "lines": false},
        "objects": [{"name": "plane", "file": "render/plane.obj",
                     "params": {"doubleSided": false},
                     "transform": {"rotate": {"axis": [1, 0, 0], "degrees": -35}}}],
        "camera": {"eye": [0, 0, )" +
            std::to_string(eyeZ) + R"(], "target": [0, 0, 0], "fov": 60}})",
        "single.json", kData);
    Renderer renderer(scene, test::glContext().info());
    renderer.render();
    const auto aovs = renderer.readAovs();
    const FloatImage& id = find(aovs, "objectId").image;
    int seen = 0;
    for (const float v : id.data) seen += v >= 0.0f;
    if (eyeZ > 0.0f)
      EXPECT_EQ(seen, id.width * id.height);
    else
      EXPECT_EQ(seen, 0);
  }
}

TEST(Frame, RejectsReadBeforeWrite) {
  test::glContext();
  Frame frame(8, 8, gl::ContextInfo{});
  const Target a = frame.declare("a", {.format = GL_RGBA8});
  const Target b = frame.declare("b", {.format = GL_RGBA8});
  frame.addPass({.name = "first", .reads = {b}, .writes = {a}, .run = [](const PassContext&) {}});
  frame.addPass({.name = "second", .reads = {a}, .writes = {b}, .run = [](const PassContext&) {}});
  try {
    frame.execute();
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("first"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("reads \"b\" before any pass writes it"),
              std::string::npos)
        << e.what();
  }
}

// An onRead pass runs when what it writes is read back, once per execute, and not at all in a
// frame nobody reads; a pass of every frame may not read what only such a pass writes.
TEST(Frame, AnOnReadPassRunsWhenItsTargetIsReadOnceAFrame) {
  test::glContext();
  Frame frame(4, 4, gl::ContextInfo{});
  const Target picture = frame.declare("picture", {.format = GL_R32F});
  const Target aov = frame.declare("aov", {.format = GL_R32F});
  int frames = 0, resolves = 0;
  frame.addPass({.name = "draw", .writes = {picture}, .run = [&](const PassContext& c) {
                   const float value = float(++frames);
                   glClearNamedFramebufferfv(c.framebuffer, GL_COLOR, 0, &value);
                 }});
  frame.addPass({.name = "resolve",
                 .reads = {picture},
                 .writes = {aov},
                 .run =
                     [&](const PassContext& c) {
                       ++resolves;
                       const float value = 10.0f * float(frames);
                       glClearNamedFramebufferfv(c.framebuffer, GL_COLOR, 0, &value);
                     },
                 .onRead = true});
  frame.execute();
  frame.execute();
  EXPECT_EQ(resolves, 0);
  EXPECT_EQ(frame.read(aov, 1), std::vector<float>(16, 20.0f));
  EXPECT_EQ(frame.read(aov, 1), std::vector<float>(16, 20.0f));
  EXPECT_EQ(resolves, 1);
  EXPECT_EQ(frame.read(picture, 1), std::vector<float>(16, 2.0f));
  EXPECT_EQ(resolves, 1);
  frame.execute();
  const gl::Framebuffer mine = gl::Framebuffer::create();  // the caller's, kept
  glBindFramebuffer(GL_FRAMEBUFFER, mine.id());
  glViewport(1, 2, 3, 4);
  (void)frame.texture(aov);
  EXPECT_EQ(resolves, 2);
  GLint bound = 0, viewport[4];
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &bound);
  glGetIntegerv(GL_VIEWPORT, viewport);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  EXPECT_EQ(GLuint(bound), mine.id());
  EXPECT_EQ(viewport[2], 3);
  EXPECT_EQ(frame.timings().size(), 1u);  // the resolve is untimed

  Frame wrong(4, 4, gl::ContextInfo{});
  const Target a = wrong.declare("a", {.format = GL_R32F});
  const Target b = wrong.declare("b", {.format = GL_R32F});
  wrong.addPass(
      {.name = "aovOnly", .writes = {a}, .run = [](const PassContext&) {}, .onRead = true});
  wrong.addPass({.name = "user", .reads = {a}, .writes = {b}, .run = [](const PassContext&) {}});
  test::expectError([&] { wrong.execute(); },
                    {"user", "reads \"a\", which only a pass run on read-back writes"});
  Frame later(4, 4, gl::ContextInfo{});
  const Target c = later.declare("c", {.format = GL_R32F});
  const Target d = later.declare("d", {.format = GL_R32F});
  later.addPass({.name = "draw", .writes = {c}, .run = [](const PassContext&) {}});
  later.addPass({.name = "aov",
                 .reads = {c},
                 .writes = {d},
                 .run = [](const PassContext&) {},
                 .onRead = true});
  later.addPass({.name = "over", .writes = {c}, .run = [](const PassContext&) {}});
  test::expectError([&] { later.execute(); },
                    {"over", "writes \"c\", which an earlier pass run on read-back uses"});
}

// A compute pass writes its target as an image; the next pass and the read-back see it. (On
// llvmpipe, which runs each dispatch to its end, a missing barrier would still pass; the GPU
// jump flooding tests run the same path on a GPU.)
TEST(Frame, AComputePassWritesItsTargetAsAnImage) {
  test::glContext();
  Frame frame(5, 3, gl::ContextInfo{});
  const Target computed = frame.declare("computed", {.format = GL_R32F});
  const Target doubled = frame.declare("doubled", {.format = GL_R32F});
  const gl::Program fill = gl::buildProgram(
      {.stages = {{GL_COMPUTE_SHADER, "fill.comp"}}, .sources = {{"fill.comp", R"(#version 450 core
layout(local_size_x = 1) in;
layout(binding = 0, r32f) uniform writeonly image2D uOut;
void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  imageStore(uOut, p, vec4(float(p.y * 5 + p.x)));
})"}}});
  const gl::Program twice = gl::buildProgram(
      {.stages = {{GL_VERTEX_SHADER, "frame/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "twice.frag"}},
       .sources = {{"twice.frag", R"(#version 450 core
layout(binding = 0) uniform sampler2D uIn;
layout(location = 0) out float outValue;
void main() { outValue = 2.0 * texelFetch(uIn, ivec2(gl_FragCoord.xy), 0).r; })"}}});
  frame.addPass({.name = "fill",
                 .writes = {computed},
                 .run =
                     [&](const PassContext& c) {
                       EXPECT_EQ(c.framebuffer, 0u);
                       glUseProgram(fill.id());
                       glBindImageTexture(0, frame.texture(computed).id(), 0, GL_FALSE, 0,
                                          GL_WRITE_ONLY, GL_R32F);
                       glDispatchCompute(GLuint(c.width), GLuint(c.height), 1);
                     },
                 .compute = true});
  frame.addPass(
      {.name = "twice", .reads = {computed}, .writes = {doubled}, .run = [&](const PassContext&) {
         glUseProgram(twice.id());
         glBindTextureUnit(0, frame.texture(computed).id());
         FullscreenTriangle().draw();
       }});
  frame.execute();
  std::vector<float> expected(15);
  for (int i = 0; i < 15; ++i) expected[std::size_t(i)] = float(i);
  EXPECT_EQ(frame.read(computed, 1), expected);
  for (float& v : expected) v *= 2.0f;
  EXPECT_EQ(frame.read(doubled, 1), expected);
}

// A handle names a target of the frame that declared it; another frame's, or a default one,
// is refused with the pass's name.
TEST(Frame, RejectsHandlesOfAnotherFrame) {
  test::glContext();
  Frame frame(8, 8, gl::ContextInfo{}), other(8, 8, gl::ContextInfo{});
  const Target foreign = other.declare("a", {.format = GL_RGBA8});
  frame.addPass({.name = "p", .writes = {foreign}, .run = [](const PassContext&) {}});
  try {
    frame.execute();
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("another frame"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("p"), std::string::npos) << e.what();
  }
  Frame third(8, 8, gl::ContextInfo{});
  third.addPass({.name = "q", .writes = {Target{}}, .run = [](const PassContext&) {}});
  EXPECT_THROW(third.execute(), Error);
  (void)third.declare("x", {});
  EXPECT_THROW((void)third.declare("x", {}), Error);  // declared twice
}

// Render targets beyond the device's limits are refused before they are made, naming the
// target, the limit and what to change; the device's own out-of-memory is reported too.
TEST(Frame, HoldsTargetsToTheDevicesLimits) {
  gl::ContextInfo device = test::glContext().info();
  ASSERT_GT(device.maxTextureSize, 0);
  ASSERT_GT(device.maxColorSamples, 0);
  device.maxTextureSize = 64;
  device.maxColorSamples = 4, device.maxIntegerSamples = 1, device.maxDepthSamples = 2;
  Frame frame(64, 48, device, std::uint64_t(3) << 20);
  test::expectError([&] { (void)frame.declare("wide", {.format = GL_RGBA8, .width = 65}); },
                    {"frame: wide: a render target of 65×48 exceeds the device's largest "
                     "texture, 64 on a side"});
  test::expectError([&] { (void)frame.declare("s", {.format = GL_RGBA8, .samples = 8}); },
                    {"frame: s: 8 samples exceed the device's 4 for this render target"});
  test::expectError([&] { (void)frame.declare("i", {.format = GL_R32I, .samples = 2}); },
                    {"2 samples exceed the device's 1"});
  test::expectError(
      [&] { (void)frame.declare("d", {.format = GL_DEPTH_COMPONENT32F, .samples = 4}); },
      {"4 samples exceed the device's 2"});
  // 64×48×4 samples×16 bytes = 192 KiB per target: the 17th passes 3 MiB.
  for (int i = 0; i < 16; ++i)
    (void)frame.declare("t" + std::to_string(i), {.format = GL_RGBA32F, .samples = 4});
  test::expectError(
      [&] { (void)frame.declare("last", {.format = GL_RGBA32F, .samples = 4}); },
      {"frame: last: the render targets need 4 MiB at 64×48, more than the 3 MiB the device "
       "has available",
       "lower the resolution or the samples"});
  // The device's own refusal (llvmpipe: a texture beyond its per-texture memory).
  const gl::ContextInfo real = test::glContext().info();
  if (real.software) {
    const int side = real.maxTextureSize;
    Frame huge(side, side, real, std::numeric_limits<std::uint64_t>::max());
    test::expectError([&] { (void)huge.declare("p", {.format = GL_RGBA32F, .samples = 4}); },
                      {"frame: p: the device could not allocate it (", " MiB, of ",
                       "a software rasteriser also limits each texture's size"});
  }
}

// What the device says it has free: for llvmpipe main memory's MemAvailable, so something and
// no more than the machine's memory.
TEST(Frame, TheDevicesAvailableMemoryIsPlausible) {
  const gl::ContextInfo device = test::glContext().info();
  const std::uint64_t available = device.availableMemory();
  if (!device.software) GTEST_SKIP() << "a GPU's driver may not tell";
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::uint64_t total = 0;
  ASSERT_TRUE(meminfo >> key >> total);
  ASSERT_EQ(key, "MemTotal:");
  EXPECT_GT(available, std::uint64_t(64) << 20);
  EXPECT_LE(available, total * 1024);
}

// A mesh beyond the triangle cap is refused before it is uploaded (a cap of 1 stands for
// 2²⁹ here, which no test machine could hold).
TEST(Frame, MeshesBeyondTheTriangleCapAreRefused) {
  test::glContext();
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  mesh.normals.assign(4, {0, 0, 1});
  mesh.triangles = {{0, 1, 2}, {1, 3, 2}};
  test::expectError([&] { GpuMesh(mesh, 1); }, {"2 triangles exceed the limit of 1 per mesh"});
  EXPECT_NO_THROW(GpuMesh(mesh, 2));
  EXPECT_EQ(GpuMesh::kMaxTriangles, std::size_t(1) << 29);
}

// A scene the device cannot hold is refused at its own keys, not with a broken frame: the
// samples and the size before any target is made, the targets' memory as the frame finds it.
TEST(Frame, AFrameTheDeviceCannotHoldIsRefusedAtTheScenesKeys) {
  const gl::ContextInfo device = test::glContext().info();
  Scene scene = planeScene(16, R"({"eye": [0, 0, -5], "target": [0, 0, 0], "fov": 60})");
  scene.file = "plane.json";
  if (device.maxColorSamples < 16)
    test::expectError([&] { Renderer renderer(scene, device); },
                      {"plane.json: /samples: 16 samples exceed the device's " +
                       std::to_string(device.maxColorSamples) + " (" + device.renderer + ")"});
  scene.samples = 1;
  gl::ContextInfo small = device;
  small.maxTextureSize = 32;
  test::expectError([&] { Renderer renderer(scene, small); },
                    {"plane.json: /resolution: 64×48 exceeds the device's largest image, 32 on a "
                     "side"});
  scene.file.clear();
  small.maxColorSamples = small.maxDepthSamples = small.maxIntegerSamples = 2;
  small.maxTextureSize = device.maxTextureSize;
  scene.samples = 4;
  test::expectError([&] { Renderer renderer(scene, small); },
                    {"scene: /samples: 4 samples exceed the device's 2"});
}

// On llvmpipe the GL_TIME_ELAPSED queries need a flush after glBeginQuery (gl/timer.cpp);
// with it, the passes' GPU times must account for the frame's wall-clock time.
TEST(Timer, PassTimesAddUpToWallClock) {
  Scene scene = parseScene(R"({"resolution": [256, 256], "samples": 4,
      "objects": [{"name": "plane", "file": "render/plane.obj"}],
      "camera": {"eye": [0, 0, 20], "target": [0, 0, 0], "fov": 40}})",
                           "timer.json", kData);
  Renderer renderer(scene, test::glContext().info());
  // The first frame's passes too: llvmpipe gives a new renderer's first query the time since
  // boot, which the timer reports as unknown (NaN).
  const auto first = std::chrono::steady_clock::now();
  renderer.render();
  glFinish();
  const double firstWall =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - first).count();
  for (const auto& t : renderer.timings())
    if (!std::isnan(t.gpuMs))
      EXPECT_LE(t.gpuMs, firstWall * 1.25 + 2.0) << t.name << " of the first frame";
  double gpu = 0, wall = 0;
  for (int i = 0; i < 5; ++i) {
    const auto start = std::chrono::steady_clock::now();
    renderer.render();
    glFinish();
    wall +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    for (const auto& t : renderer.timings()) {
      EXPECT_GE(t.gpuMs, 0.0) << t.name;
      gpu += t.gpuMs;
    }
  }
  // A timer cannot measure much more than the wall clock: 25% + 2 ms for llvmpipe's query
  // bookkeeping, which its own threads time, seen at +12% under the sanitizers; on a
  // software rasteriser the GPU work is most of the frame, so it must explain at least a fifth
  // of it even with another test process competing for the two cores.
  EXPECT_LE(gpu, wall * 1.25 + 2.0) << "gpu " << gpu << " ms, wall " << wall << " ms";
  if (test::glContext().info().software)
    EXPECT_GE(gpu, wall / 5.0) << "gpu " << gpu << " ms, wall " << wall << " ms";
}

// A raster terrain is a grid mesh: drawn at the detail its pixel error allows (Scene::pixelError,
// cutaway/geometry/grid_lod.hpp), with far fewer triangles and the same picture up to edges
// moved by a pixel and the shading's small changes; at 0, every triangle.
TEST(Renderer, ARasterTerrainIsDrawnAtTheDetailItsPixelErrorAllows) {
  const std::filesystem::path dem = test::scratchPath("lod", "dem.tif");
  writeSyntheticDem(dem, {.min = {500000, 4000000},
                          .max = {502560, 4002560},
                          .crs = "EPSG:32633",
                          .cell = 10,
                          .base = 100,
                          .relief = 120,
                          .wavelength = 900});
  const auto render = [&](float pixelError, std::size_t& triangles) {
    Scene scene = parseScene(R"({"geo": {"crs": "EPSG:32633", "offset": [501280, 4001280, 0]},
        "resolution": [320, 240], "samples": 1, "style": {"name": "blinn-phong", "lines": false},
        "objects": [{"name": "ground", "raster": {"file": "dem.tif"}}],
        "camera": {"eye": [-1500, 900, 1500], "target": [0, 100, 0], "fov": 45}})",
                             "lod.json", dem.parent_path());
    EXPECT_TRUE(scene.objects[0].mesh->grid);
    scene.pixelError = pixelError;
    Renderer renderer(scene, test::glContext().info());
    renderer.render();
    triangles = renderer.meshTriangles();
    return renderer.readColor();
  };
  std::size_t full = 0, half = 0, four = 0;
  const Rgba8Image whole = render(0.0f, full);
  EXPECT_EQ(full, 2u * 255u * 255u);
  const Rgba8Image coarser = render(0.5f, half);
  (void)render(4.0f, four);
  EXPECT_LT(half, full / 2);
  EXPECT_LT(four, half);
  const test::ImageDifference d = test::compareImages(whole, coarser, 16);
  EXPECT_EQ(d.unexplained, 0) << "max difference " << d.maxDifference;
  // The shading follows the kept nodes' normals, interpolated over larger triangles: a
  // difference of a few levels here and there (0.61 on average here).
  EXPECT_LT(d.meanDifference, 1.0);
  std::printf("triangles at 0, 0.5 and 4 px: %zu, %zu, %zu; mean difference %.3f\n", full, half,
              four, d.meanDifference);
}

// A mesh with coarser versions (SceneObject::coarser; a network's shafts with 16, 8 and 4
// sides) is drawn as the coarsest whose error r (1 − cos(π/n)) spans at most the pixel error at
// the mesh's nearest point (K / d pixels per unit); outside the view, the coarsest; at a pixel
// error of 0, the mesh itself.
TEST(Frame, AMeshWithCoarserVersionsIsDrawnAsTheCoarsestWithinThePixelError) {
  test::glContext();
  PipeNetwork net;
  net.shafts.push_back(Shaft{.bottom = {0, -3, 0}, .top = 0.0f, .radius = 1.0f});
  const SceneObject shafts = shaftObject(net, 0, false);
  ASSERT_EQ(shafts.coarser.size(), 3u);
  std::vector<std::size_t> triangles = {shafts.mesh->triangles.size()};
  for (int k = 0; k < 3; ++k) {
    const int sides = 16 >> k;
    EXPECT_FLOAT_EQ(shafts.coarser[std::size_t(k)].error,
                    1.0f - std::cos(glm::pi<float>() / float(sides)));
    triangles.push_back(shafts.coarser[std::size_t(k)].mesh->triangles.size());
    EXPECT_EQ(triangles.back(), std::size_t(2 * sides));
  }
  GpuMesh mesh(*shafts.mesh, shafts.coarser);
  EXPECT_EQ(mesh.triangles(), 64u);
  GridLod::View view;
  view.projection = glm::perspective(glm::radians(45.0f), 1.0f, 0.1f, 1e5f);
  view.viewportHeight = 1000.0f;
  view.pixelError = 0.5f;
  const float k = 500.0f / std::tan(glm::radians(22.5f));
  // Eyes along +z, the shaft's nearest point at distance d − 1 (its radius).
  for (const float d : {20.0f, 100.0f, 400.0f, 2000.0f, 20000.0f}) {
    view.eye = {0.0f, -1.5f, d};
    view.viewProjection =
        view.projection * glm::lookAt(view.eye, glm::vec3(0, -1.5f, 0), glm::vec3(0, 1, 0));
    std::size_t expected = 0;
    while (expected < 3 && shafts.coarser[expected].error * k / (d - 1.0f) <= view.pixelError)
      ++expected;
    mesh.selectDetail(view);
    EXPECT_EQ(mesh.triangles(), triangles[expected]) << "at distance " << d;
  }
  view.pixelError = 0.0f;
  mesh.selectDetail(view);
  EXPECT_EQ(mesh.triangles(), 64u);
  view.viewProjection =
      view.projection * glm::lookAt(view.eye, view.eye + glm::vec3(0, 0, 1), glm::vec3(0, 1, 0));
  mesh.selectDetail(view);
  EXPECT_EQ(mesh.triangles(), 8u) << "turned away";
}

// The line passes' normal targets (frame/normal_weight.glsl): a unit normal and a line weight in
// one word, through the shader's own pack and unpack. Normals on the axes come back exact, every
// other (a Fibonacci sphere, the octahedron's seams, near-axis tilts) within 0.06°; weights k/255
// exactly, others clamped to [0, 1]; a cleared word (0) is weight 0.
TEST(Frame, PackedNormalsAndLineWeightsRoundTrip) {
  test::glContext();
  std::vector<glm::vec4> in;  // xyz: the normal, w: the weight
  for (int axis = 0; axis < 3; ++axis)
    for (const float sign : {1.0f, -1.0f}) {
      glm::vec4 v(0.0f);
      v[axis] = sign;
      in.push_back(v);
    }
  const int sphere = 20000;
  for (int i = 0; i < sphere; ++i) {  // spherical Fibonacci points
    const float z = 1.0f - 2.0f * (float(i) + 0.5f) / float(sphere);
    const float phi = float(i) * glm::pi<float>() * (3.0f - std::sqrt(5.0f));
    const float r = std::sqrt(1.0f - z * z);
    in.emplace_back(r * std::cos(phi), r * std::sin(phi), z, 0.0f);
  }
  for (const float t : {1e-4f, 1e-3f, 0.3f, 0.5f, 0.7f, 0.999f})  // seams and near the axes
    for (const float sx : {1.0f, -1.0f})
      for (const float sz : {1.0f, -1.0f}) {
        in.emplace_back(glm::normalize(glm::vec3(sx * t, 1.0f - t, sz * 1e-3f)), 0.0f);
        in.emplace_back(glm::normalize(glm::vec3(sx * t, 1e-5f, sz)), 0.0f);
      }
  for (std::size_t i = 0; i < in.size(); ++i)
    in[i].w = i < 256 ? float(i) / 255.0f : i % 3 == 0 ? -0.5f : i % 3 == 1 ? 7.0f : 0.31f;
  const GLsizeiptr bytes = GLsizeiptr(in.size() * sizeof(glm::vec4));
  const gl::Buffer input = gl::Buffer::create(bytes, in.data());
  const gl::Buffer output = gl::Buffer::create(bytes, nullptr, GL_DYNAMIC_STORAGE_BIT);
  const gl::Buffer words =
      gl::Buffer::create(GLsizeiptr(in.size() * sizeof(GLuint)), nullptr, GL_DYNAMIC_STORAGE_BIT);
  const gl::Program roundTrip =
      gl::buildProgram({.stages = {{GL_COMPUTE_SHADER, "round_trip.comp"}},
                        .sources = {{"round_trip.comp", R"(#version 450 core
#include "frame/normal_weight.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer In { vec4 uIn[]; };
layout(std430, binding = 1) writeonly buffer Out { vec4 uOut[]; };
layout(std430, binding = 2) writeonly buffer Words { uint uWords[]; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uint(uIn.length())) return;
  uint word = packNormalWeight(uIn[i].xyz, uIn[i].w);
  uWords[i] = word;
  uOut[i] = vec4(unpackNormal(word), unpackWeight(word));
})"}}});
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, input.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, output.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, words.id());
  glUseProgram(roundTrip.id());
  glDispatchCompute(GLuint((in.size() + 63) / 64), 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<glm::vec4> out(in.size());
  glGetNamedBufferSubData(output.id(), 0, bytes, out.data());
  double worst = 0.0;
  for (std::size_t i = 0; i < in.size(); ++i) {
    SCOPED_TRACE(i);
    const glm::dvec3 a = glm::dvec3(in[i]), b = glm::dvec3(out[i]);
    if (i < 6) EXPECT_EQ(glm::vec3(out[i]), glm::vec3(in[i]));  // the axes
    const double degrees = glm::degrees(std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)));
    worst = std::max(worst, degrees);
    EXPECT_NEAR(glm::length(b), 1.0, 1e-6);
    EXPECT_EQ(out[i].w, std::clamp(std::round(in[i].w * 255.0f), 0.0f, 255.0f) / 255.0f);
  }
  EXPECT_LE(worst, 0.06) << "degrees";
  EXPECT_GT(worst, 0.001) << "degrees: the 12-bit grid shows";  // the test sees the rounding
  // A cleared target (word 0) holds no line.
  std::vector<GLuint> packed(in.size());
  glGetNamedBufferSubData(words.id(), 0, GLsizeiptr(packed.size() * sizeof(GLuint)), packed.data());
  for (std::size_t i = 0; i < in.size(); ++i)
    if (out[i].w == 0.0f) EXPECT_EQ(packed[i] >> 24, 0u) << i;
}
