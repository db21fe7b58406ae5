// Volumes as a geometry kind (src/kinds/volumes): the GPU ray caster against the CPU reference
// (kinds/volumes/volume_ray_cast.cpp) pixel by pixel, the CPU reference against closed forms (a
// sampled sphere's isosurface, the emission–absorption integral of a constant block), depth
// against meshes inside, the cutters deciding ray samples (the box cut's C++ mirror, the
// adaptive cutaway's surface), and the scene file's checks.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cutaway/cutters/box_cut.hpp"
#include "cutaway/cutters/clip_surfaces.hpp"
#include "cutaway/cutters/cutout.hpp"
#include "cutaway/kinds/volume_ray_cast.hpp"
#include "cutaway/render/renderer.hpp"
#include "cutaway/scene/scene.hpp"
#include "expect_error.hpp"
#include "gl_test_context.hpp"
#include "mismatches.hpp"
#include "render_aovs.hpp"

namespace fs = std::filesystem;
using namespace cutaway;
using test::aov;
using test::expectError;
using test::renderAovs;

namespace {

const std::string kData = CUTAWAY_TEST_DATA;

class VolumeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // A parameterised test's name has a '/', which would make a folder inside another.
    std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    std::replace(name.begin(), name.end(), '/', '_');
    dir_ =
        fs::temp_directory_path() / ("cutaway-volumes-" + std::to_string(::getpid()) + "-" + name);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // A float volume of n³ voxels, voxel centres from −h to h on each axis (spacing 2h/(n−1)),
  // with value f(world point); returns its JSON header's path.
  template <class F>
  fs::path volume(const std::string& name, int n, float h, F f) {
    const float spacing = 2.0f * h / float(n - 1);
    std::vector<float> values;
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
          values.push_back(f(glm::vec3(-h) + spacing * glm::vec3(i, j, k)));
    std::ofstream(dir_ / (name + ".raw"), std::ios::binary)
        .write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * 4));
    const std::string s = std::to_string(spacing), o = std::to_string(-h);
    std::ofstream(dir_ / (name + ".json"))
        << R"({"file": ")" << name << R"(.raw", "dims": [)" << n << ", " << n << ", " << n
        << R"(], "type": "f32", "spacing": [)" << s << ", " << s << ", " << s << R"(], "origin": [)"
        << o << ", " << o << ", " << o << "]}";
    return dir_ / (name + ".json");
  }

  // One volume on black, 96² pixels seen orthographically along −z over [−0.8, 0.8]², no
  // feature lines: what the closed-form checks look at.
  Scene alongZ(const std::string& volume) {
    return parseScene(R"({"resolution": [96, 96], "samples": 1, "background": [0, 0, 0],
      "style": {"name": "gooch", "lines": false},
      "camera": {"projection": "orthographic", "height": 1.6, "eye": [0, 0, 4], "target": [0, 0, 0]},
      "volumes": [)" + volume +
                          "]}",
                      "along-z.json", dir_);
  }

  Scene scene(const std::string& volumes, const std::string& rest = "") {
    const std::string text = R"({"resolution": [96, 72], "samples": 1, "background": [0, 0, 0],
      "style": {"name": "gooch", "lines": false},
      "camera": {"eye": [0.6, 0.9, 4.0], "target": [0, 0, 0], "fov": 40},
      "volumes": [)" + volumes +
                             "]" + rest + "}";
    return parseScene(text, "volumes.json", dir_);
  }

  // A block of one material (value 0.6, opacity 0.3, the given importance) around a cube of
  // interest, cut by the contextual structure (θ 30°, θ₂ 55°, d 0.3, R from importance) applied
  // as `apply`; 128² with a 128² cutaway buffer, so that a pixel centre is a texel centre of C₁
  // and C₂.
  Scene contextualBlock(float importance, const std::string& apply) {
    const fs::path file = volume("block", 24, 1.0f, [](glm::vec3) { return 0.6f; });
    Scene s = scene(R"({"name": "block", "file": ")" + file.string() +
                        R"(", "shading": false, "jitter": false,
                    "transferFunction": [{"value": 0.6, "color": [0.8, 0.7, 0.6], "opacity": 0.3,
                                          "importance": )" +
                        std::to_string(importance) + "}]}",
                    R"(, "objects": [{"name": "probe", "file": ")" + kData +
                        R"(/meshes/cube.obj", "role": "interest",
                          "transform": {"translate": [-0.25, -0.25, -0.25], "scale": 0.5}}],
                    "cutters": {"adaptive": {"angle": 30, "bufferSize": 128,
                      "contextual": {"transitionAngle": 55, "overlay": 0.3,
                                     "reduction": "importance", "apply": ")" +
                        apply + R"("}}})");
    s.width = s.height = 128;
    return s;
  }

  fs::path dir_;
};

glm::vec4 pixel(const FloatImage& image, int x, int y) {
  const float* v = image.at(x, y);
  return {v[0], image.channels > 1 ? v[1] : 0.0f, image.channels > 2 ? v[2] : 0.0f,
          image.channels > 3 ? v[3] : 0.0f};
}

// The view ray through uv (window coordinates in [0, 1], y up) of the inverse view-projection:
// its origin on the near plane and unit direction.
struct PixelRay {
  glm::vec3 o, d;
};
PixelRay pixelRay(const glm::mat4& inverseViewProjection, glm::vec2 uv) {
  const glm::vec4 a = inverseViewProjection * glm::vec4(uv * 2.0f - 1.0f, -1.0f, 1.0f);
  const glm::vec4 b = inverseViewProjection * glm::vec4(uv * 2.0f - 1.0f, 1.0f, 1.0f);
  const glm::vec3 o = glm::vec3(a) / a.w;
  return {o, glm::normalize(glm::vec3(b) / b.w - o)};
}

// The view distance of window depth `windowDepth` (perspective: the same at every pixel).
float viewDistance(const glm::mat4& inverseProjection, float windowDepth) {
  const glm::vec4 h = inverseProjection * glm::vec4(0.0f, 0.0f, 2.0f * windowDepth - 1.0f, 1.0f);
  return -h.z / h.w;
}

// The distance along the ray from o (unit direction d) to the sphere |x| = r; < 0: a miss.
float sphereHit(glm::vec3 o, glm::vec3 d, float r) {
  const float b = glm::dot(o, d), c = glm::dot(o, o) - r * r, disc = b * b - c;
  return disc < 0.0f ? -1.0f : -b - std::sqrt(disc);
}

const char* kRamp = R"("transferFunction": [
    {"value": 0.0, "color": [0.2, 0.4, 1.0], "opacity": 0.0, "importance": 0.2},
    {"value": 0.5, "color": [1.0, 0.6, 0.2], "opacity": 0.08, "importance": 0.5},
    {"value": 1.0, "color": [1.0, 1.0, 1.0], "opacity": 0.3, "importance": 1.0}])";

}  // namespace

TEST(TransferFunction, InterpolatesLinearlyAndHoldsItsEnds) {
  TransferFunction tf{{{0.0f, {{0.0f, {0, 0, 0}, 0.0f, 0.0f}, {2.0f, {1, 0.5f, 0}, 0.4f, 1.0f}}}}};
  EXPECT_FLOAT_EQ(tf.at(1.0f).opacity, 0.2f);
  EXPECT_FLOAT_EQ(tf.at(1.0f).color.g, 0.25f);
  EXPECT_FLOAT_EQ(tf.at(0.5f).importance, 0.25f);
  EXPECT_FLOAT_EQ(tf.at(-5.0f).opacity, 0.0f);
  EXPECT_FLOAT_EQ(tf.at(7.0f).opacity, 0.4f);
}

TEST_F(VolumeTest, TheCpuRayCasterIntegratesAConstantBlockInClosedForm) {
  // A block of constant value: n samples of opacity α' each leave 1 − (1 − α)^(n·Δs/d).
  const fs::path file = volume("block", 16, 1.0f, [](glm::vec3) { return 1.0f; });
  Scene s = scene(R"({"name": "b", "file": ")" + file.string() +
                  R"(", "jitter": false, "sampleDistance": 0.25, "opacityDistance": 2,
                  "transferFunction": [{"value": 0, "opacity": 0}, {"value": 1, "opacity": 0.1}]})");
  s.camera.fit = false;
  s.camera.projection = Projection::Orthographic;
  s.camera.eye = {0.0f, 0.0f, 5.0f};
  s.camera.target = {0.0f, 0.0f, 0.0f};
  const Camera c = s.resolvedCamera();
  const float aspect = float(s.width) / float(s.height);
  const SceneVolume& v = s.volumes[0];
  const VolumeRay r = castVolumeRay(v, c.view(), c.projectionMatrix(aspect), {s.width, s.height},
                                    {s.width / 2, s.height / 2});
  // The box spans [−1 − ½Δ, 1 + ½Δ] along z with Δ = 2/15; samples every Δ/4 from its front
  // plus half a step.
  const float delta = 2.0f / 15.0f, length = 2.0f + delta, step = 0.25f * delta;
  const int samples = int(std::ceil(length / step - 0.5f));
  const float expected = 1.0f - std::pow(0.9f, samples * 0.25f / 2.0f);
  EXPECT_NEAR(r.opacity, expected, 1e-4f);
  EXPECT_NEAR(r.entryDepth, 5.0f - (1.0f + 0.5f * delta) + 0.5f * step, 1e-4f);
  EXPECT_NEAR(r.color.r, expected, 1e-4f);  // white emission, premultiplied
}

// The GPU's isosurface of a sampled sphere lies where the sphere is, within a tenth of a
// voxel; the CPU's too.
TEST_F(VolumeTest, TheIsosurfaceOfASampledSphereIsTheSphere) {
  const float radius = 0.7f;
  const fs::path file =
      volume("sphere", 40, 1.0f, [&](glm::vec3 p) { return radius - glm::length(p); });
  const Scene s = scene(R"({"name": "sphere", "file": ")" + file.string() +
                        R"(", "mode": "isosurface", "isoValue": 0, "sampleDistance": 0.5,
                        "transferFunction": [{"value": 0, "color": [0.9, 0.8, 0.7], "opacity": 1}]})");
  const auto aovs = renderAovs(s);
  const FloatImage& hit = aov(aovs, "volumeHitDepth");
  const Camera c = s.resolvedCamera();
  const float aspect = float(s.width) / float(s.height);
  const glm::mat4 inverse = glm::inverse(c.projectionMatrix(aspect) * c.view());
  const float voxel = 2.0f / 39.0f;
  int hits = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const glm::vec2 uv((x + 0.5f) / s.width, 1.0f - (y + 0.5f) / s.height);
      const auto [o, d] = pixelRay(inverse, uv);
      const float t = sphereHit(o, d, radius);
      // Only rays clearly inside the silhouette (not grazing within a voxel of it).
      if (sphereHit(o, d, radius + voxel) < 0.0f || sphereHit(o, d, radius - voxel) < 0.0f)
        continue;
      ++hits;
      const float expected = -(c.view() * glm::vec4(o + t * d, 1.0f)).z;
      ASSERT_FALSE(std::isnan(hit.at(x, y)[0])) << x << "," << y;
      EXPECT_NEAR(hit.at(x, y)[0], expected, 0.1f * voxel) << x << "," << y;
      const VolumeRay cpu = castVolumeRay(s.volumes[0], c.view(), c.projectionMatrix(aspect),
                                          {s.width, s.height}, {x, s.height - 1 - y});
      EXPECT_NEAR(cpu.hitDepth, expected, 0.1f * voxel) << x << "," << y;
    }
  EXPECT_GT(hits, 500);
}

// A volume 1e-13 across rendered blank with exit 0: the float inverse of its voxel-to-world
// transform divided by a determinant that underflowed (1e-39). Scaled down with its camera, a
// shaded sphere is the same picture; below 1e-15 across, where normals' squared lengths
// underflow too, a volume (and its voxels) is refused, naming it.
TEST_F(VolumeTest, AVolumeScaledDownWithItsCameraIsTheSamePicture) {
  const fs::path file =
      volume("sphere", 24, 1.0f, [](glm::vec3 p) { return 0.7f - glm::length(p); });
  const auto at = [&](const std::string& scale) {
    const std::string eye = "[" + scale + ", " + scale + ", " + "4" + scale.substr(1) + "]";
    return R"({"resolution": [64, 48], "samples": 1, "background": [0, 0, 0],
      "style": {"name": "gooch", "lines": false},
      "camera": {"eye": )" +
           eye + R"(, "target": [0, 0, 0], "fov": 40},
      "volumes": [{"name": "sphere", "file": ")" +
           file.string() + R"(", "transform": {"scale": )" + scale +
           R"(}, "mode": "isosurface", "isoValue": 0,
        "transferFunction": [{"value": 0, "color": [0.9, 0.8, 0.7], "opacity": 1}]}]})";
  };
  const auto colour = [&](const std::string& scale) {
    const Scene s = parseScene(at(scale), "small.json", dir_);
    Renderer renderer(s, test::glContext().info());
    renderer.render();
    return renderer.readColor();
  };
  const Rgba8Image whole = colour("1e0");
  int lit = 0;
  for (int y = 0; y < whole.height; ++y)
    for (int x = 0; x < whole.width; ++x) lit += whole.at(x, y)[0] > 0;
  EXPECT_GT(lit, 300);
  for (const std::string scale : {"1e-12", "1e-13"}) {  // voxels 8.7e-14 and 8.7e-15 apart
    const Rgba8Image small = colour(scale);
    int worst = 0;
    for (int y = 0; y < whole.height; ++y)
      for (int x = 0; x < whole.width; ++x)
        for (int k = 0; k < 3; ++k)
          worst = std::max(worst, std::abs(int(small.at(x, y)[k]) - int(whole.at(x, y)[k])));
    EXPECT_LE(worst, 2) << scale;
  }
  expectError([&] { (void)parseScene(at("1e-16"), "small.json", dir_); },
              {"small.json", "/volumes/0", "\"sphere\" measures", "smaller than 1e-15"});
}

namespace {

float blinnSpecular(glm::vec3 n, glm::vec3 l, glm::vec3 v, float shininess) {
  if (glm::dot(n, l) <= 0.0f) return 0.0f;
  return std::pow(std::max(glm::dot(n, glm::normalize(l + v)), 0.0f), shininess);
}

// The scene style written as JSON (`{"name": …}`).
Style parseStyle(const std::string& json) {
  return parseScene(
             R"({"style": )" + json + R"(, "objects": [{"name": "c", "file": "meshes/cube.obj"}]})",
             "style.json", kData)
      .style;
}

glm::mat4 inverseViewProjection(const Scene& s) {
  const Camera c = s.resolvedCamera();
  return glm::inverse(c.projectionMatrix(float(s.width) / float(s.height)) * c.view());
}

// The largest difference, in levels of 255, between rendered pixels and their expected colours.
struct WorstPixel {
  double levels = 0.0;
  std::string where;
  void compare(const Rgba8Image& color, int x, int y, glm::vec3 expected) {
    for (int k = 0; k < 3; ++k) {
      const double error = std::abs(color.at(x, y)[k] / 255.0 - expected[k]) * 255.0;
      if (error > levels)
        levels = error, where = std::to_string(x) + "," + std::to_string(y) + " channel " +
                                std::to_string(k) + ": " + std::to_string(color.at(x, y)[k]) +
                                " vs " + std::to_string(expected[k] * 255.0f);
    }
  }
};

}  // namespace

// Volume samples are shaded by the scene's style with their gradient normals, then emphasised
// by their material's importance (Burns11 §3.3.1, eqs. 3.1–3.4): an isosurface of a sampled
// sphere, each pixel against the style's formula written out here at the sphere's analytic
// hit point and normal (a volume sample's specular weight is 0.2, its shininess 32).
TEST_F(VolumeTest, IsosurfacesAreShadedByTheStyleAndEmphasisedByImportance) {
  const float radius = 0.7f;
  const fs::path file =
      volume("sphere", 48, 1.0f, [&](glm::vec3 p) { return radius - glm::length(p); });
  const glm::vec3 kd(0.7f, 0.35f, 0.2f), blue(0.1f, 0.1f, 0.6f), yellow(0.5f, 0.4f, 0.0f);
  const glm::vec3 l = -glm::normalize(glm::vec3(-0.5f, -0.7f, -0.3f));
  const float importance = 0.25f, ec = 0.6f, es = 0.5f;
  struct Case {
    const char* style;
    std::function<glm::vec3(glm::vec3 n, glm::vec3 v)> shade;
    bool emphasis;
  };
  const auto blinnPhong = [&](glm::vec3 n, glm::vec3 v) {
    return 0.1f * kd + kd * std::max(glm::dot(n, l), 0.0f) +
           glm::vec3(0.2f * blinnSpecular(n, l, v, 32.0f));
  };
  const auto gooch = [&](glm::vec3 n, glm::vec3 v) {
    const float t = 0.5f * (1.0f + glm::dot(n, l));
    return t * (yellow + 0.6f * kd) + (1.0f - t) * (blue + 0.3f * kd) +
           glm::vec3(0.2f * blinnSpecular(n, l, v, 32.0f));
  };
  const Case cases[] = {
      {R"({"name": "blinn-phong", "lines": false, "blinnPhong": {"ambient": 0.1}})", blinnPhong,
       false},
      {R"({"name": "gooch", "lines": false, "gooch": {"cool": [0.1, 0.1, 0.6],
           "warm": [0.5, 0.4, 0.0], "alpha": 0.3, "beta": 0.6}})",
       gooch, false},
      {R"({"name": "blinn-phong", "lines": false, "blinnPhong": {"ambient": 0.1},
           "emphasis": {"color": 0.6, "shading": 0.5}})",
       blinnPhong, true},
  };
  for (const Case& c : cases) {
    Scene s = scene(R"({"name": "sphere", "file": ")" + file.string() +
                        R"(", "mode": "isosurface", "isoValue": 0, "sampleDistance": 0.5,
                    "transferFunction": [{"value": 0, "color": [0.7, 0.35, 0.2], "opacity": 1,
                                          "importance": 0.25}]})",
                    std::string(R"(, "lights": [{"type": "directional",
                    "direction": [-0.5, -0.7, -0.3], "space": "world"}])"));
    s.style = parseStyle(c.style);
    Renderer renderer(s, test::glContext().info());
    renderer.render();
    const Rgba8Image color = renderer.readColor();  // rows top to bottom
    const Camera camera = s.resolvedCamera();
    const glm::mat4 inverse = inverseViewProjection(s);
    const float voxel = 2.0f / 47.0f;
    WorstPixel worst;
    int compared = 0;
    for (int y = 0; y < s.height; ++y)
      for (int x = 0; x < s.width; ++x) {
        const glm::vec2 uv((x + 0.5f) / s.width, 1.0f - (y + 0.5f) / s.height);
        const auto [o, d] = pixelRay(inverse, uv);
        // Rays clearly inside the silhouette, where the hit's normal turns slowly.
        if (sphereHit(o, d, radius + 2.0f * voxel) < 0.0f ||
            sphereHit(o, d, radius - 3.0f * voxel) < 0.0f)
          continue;
        const glm::vec3 q = o + sphereHit(o, d, radius) * d;
        glm::vec3 expected = c.shade(glm::normalize(q), glm::normalize(camera.eye - q));
        if (c.emphasis) {
          // Eqs. 3.3–3.4: shading suppressed towards the unshaded colour; eqs. 3.1–3.2: then
          // greyed towards its Rec. 709 luma.
          const glm::vec3 suppressed = glm::mix(expected, kd, es * (1.0f - importance));
          const float luma = glm::dot(suppressed, glm::vec3(0.2126f, 0.7152f, 0.0722f));
          expected = glm::mix(suppressed, glm::vec3(luma), ec * (1.0f - importance));
        }
        worst.compare(color, x, y, glm::clamp(expected, 0.0f, 1.0f));
        ++compared;
      }
    // The gradient's central differences and its half floats, and the hit placed by linear
    // interpolation between samples, against the analytic sphere.
    EXPECT_LE(worst.levels, 3.0) << c.style << ": worst pixel " << worst.where;
    std::printf("%s: worst %.2f levels\n", c.style, worst.levels);
    EXPECT_GT(compared, 500) << c.style;
  }
}

// Analytic: a solid box [−0.8, 0.8]³ with a spherical cavity of radius 0.5 at its centre,
// rendered as an isosurface, its front half (z > 0) removed by a box cut. Along a ray that
// meets the plane z = 0 inside the box and outside the cavity, the surface is the cut's face on
// that plane (the first kept sample, within a step), lit as a face with the plane's normal
// (Burns11 §5.2.4.1 on volumes); a ray through the cavity's opening meets the cavity's far wall,
// |q| = 0.5, placed between samples (within a tenth of a voxel) and lit by the wall's gradient
// normal. Colours against Blinn-Phong written out here (a volume sample's specular weight 0.2,
// shininess 32).
TEST_F(VolumeTest, ABoxWithACavityCutOpenShowsTheCutFaceAndTheCavitysFarWall) {
  const float half = 0.8f, radius = 0.5f;
  const fs::path file = volume("cavity", 48, 1.0f, [&](glm::vec3 p) {
    const glm::vec3 a = glm::abs(p);
    return std::min(half - std::max({a.x, a.y, a.z}), glm::length(p) - radius);
  });
  const glm::vec3 kd(0.7f, 0.35f, 0.2f);
  const glm::vec3 l = -glm::normalize(glm::vec3(-0.5f, -0.7f, -0.3f));
  Scene s = scene(R"({"name": "cavity", "file": ")" + file.string() +
                      R"(", "mode": "isosurface", "isoValue": 0, "sampleDistance": 0.5,
                  "transferFunction": [{"value": 0, "color": [0.7, 0.35, 0.2], "opacity": 1}]})",
                  R"(, "lights": [{"type": "directional", "direction": [-0.5, -0.7, -0.3],
                                   "space": "world"}],
                     "cutters": {"boxCut": {"center": [0, 0, 1], "size": [3, 3, 2]}})");
  s.style =
      parseStyle(R"({"name": "blinn-phong", "lines": false, "blinnPhong": {"ambient": 0.1}})");
  Renderer renderer(s, test::glContext().info());
  renderer.render();
  const Rgba8Image color = renderer.readColor();  // rows top to bottom
  const auto aovs = renderer.readAovs();
  const FloatImage& hit = aov(aovs, "volumeHitDepth");
  const Camera camera = s.resolvedCamera();
  const glm::mat4 inverse = inverseViewProjection(s);
  const float voxel = 2.0f / 47.0f, step = 0.5f * voxel;
  const auto shade = [&](glm::vec3 n, glm::vec3 q) {
    const glm::vec3 v = glm::normalize(camera.eye - q);
    if (glm::dot(n, v) < 0.0f) n = -n;
    return glm::clamp(0.1f * kd + kd * std::max(glm::dot(n, l), 0.0f) +
                          glm::vec3(0.2f * blinnSpecular(n, l, v, 32.0f)),
                      0.0f, 1.0f);
  };
  int face = 0, wall = 0;
  WorstPixel worst;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const glm::vec2 uv((x + 0.5f) / s.width, 1.0f - (y + 0.5f) / s.height);
      const auto [o, d] = pixelRay(inverse, uv);
      const glm::vec3 onPlane = o - o.z / d.z * d;
      const glm::vec2 a = glm::abs(glm::vec2(onPlane));
      const float r = glm::length(glm::vec2(onPlane));
      const float depth = hit.at(x, y)[0];
      glm::vec3 expected;
      if (std::max(a.x, a.y) < half - 2.0f * voxel && r > radius + 2.0f * voxel) {
        const float planeDepth = -(camera.view() * glm::vec4(onPlane, 1.0f)).z;
        ASSERT_FALSE(std::isnan(depth)) << x << "," << y;
        EXPECT_GE(depth, planeDepth - 0.1f * voxel) << x << "," << y;
        EXPECT_LE(depth, planeDepth + step + 0.1f * voxel) << x << "," << y;
        expected = shade({0.0f, 0.0f, 1.0f}, onPlane);
        ++face;
      } else if (r < radius - 3.0f * voxel) {
        const float b = glm::dot(o, d), c = glm::dot(o, o) - radius * radius;
        const glm::vec3 q = o + (-b + std::sqrt(b * b - c)) * d;  // the far root: from inside
        ASSERT_FALSE(std::isnan(depth)) << x << "," << y;
        EXPECT_NEAR(depth, -(camera.view() * glm::vec4(q, 1.0f)).z, 0.1f * voxel) << x << "," << y;
        expected = shade(-glm::normalize(q), q);
        ++wall;
      } else {
        continue;
      }
      worst.compare(color, x, y, expected);
    }
  // As the sphere's isosurface: central differences and half floats against the analytic
  // normal; the face's normal is exact.
  EXPECT_LE(worst.levels, 3.0) << "worst pixel " << worst.where;
  EXPECT_GT(face, 300);
  EXPECT_GT(wall, 150);
}

// Maximum intensity projection against its definition: a Gaussian blob's largest value along
// a ray is exp(−k·d²), d the ray's distance from the blob's centre, so with a white transfer
// function whose opacity is the value (the pixel is colour × opacity over black) each pixel of
// an orthographic view along z is 255·exp(−k·d²). Allowed: trilinear interpolation's bound
// (h²/8)·(|f_xx| + |f_yy| + |f_zz|) ≤ (h²/8)·6k, plus a level for the steps and 8 bits.
TEST_F(VolumeTest, TheMaximumModeShowsTheLargestValueAlongEachRay) {
  const glm::vec3 centre(0.1f, -0.05f, 0.2f);
  const float k = 6.0f;
  const fs::path file = volume("gauss", 48, 1.0f, [&](glm::vec3 p) {
    return std::exp(-k * glm::dot(p - centre, p - centre));
  });
  const Scene s = alongZ(R"({"name": "gauss", "file": ")" + file.string() +
                         R"(", "mode": "maximum", "shading": false, "transferFunction": [
                           {"value": 0, "color": [1, 1, 1], "opacity": 0},
                           {"value": 1, "color": [1, 1, 1], "opacity": 1}]})");
  Renderer renderer(s, test::glContext().info());
  renderer.render();
  const Rgba8Image color = renderer.readColor();
  const Camera c = s.resolvedCamera();
  const glm::mat4 inverse = glm::inverse(c.projectionMatrix(1.0f) * c.view());
  double worst = 0.0;
  int bright = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const glm::vec4 h =
          inverse * glm::vec4((x + 0.5f) / float(s.width) * 2.0f - 1.0f,
                              1.0f - (y + 0.5f) / float(s.height) * 2.0f, 0.0f, 1.0f);
      const glm::vec2 onRay = glm::vec2(h) / h.w;  // the ray runs along z
      const glm::vec2 off = onRay - glm::vec2(centre);
      const float m = std::exp(-k * glm::dot(off, off));
      const double expected = 255.0 * m;
      bright += expected > 128.0;
      for (int ch = 0; ch < 3; ++ch)
        worst = std::max(worst, std::abs(color.at(x, y)[ch] - expected));
    }
  const double h = 2.0 / 47.0, bound = 255.0 * h * h / 8.0 * 6.0 * k + 1.0;
  std::printf("maximum intensity: %d bright pixels, worst %.2f levels (bound %.2f)\n", bright,
              worst, bound);
  EXPECT_GT(bright, 500);
  EXPECT_LE(worst, bound);
}

// Emission–absorption against its closed form (Burns11 §5.2.5): through a box of uniform
// material (one transfer-function colour and opacity α per opacityDistance d voxels) a ray
// of length L keeps T = (1 − α)^(L/(d·s)), s the spacing, whatever the step, when the steps
// tile L. An orthographic view along z sends every ray through the box's whole depth
// L = n·s (its cell edges), so each pixel's accumulated opacity is 1 − T and, white over
// black, its colour 255·(1 − T). With steps that do not tile L, a ray takes ⌈L/h − o⌉ samples
// for its jitter offset o: 136 or 137 here, on average L/h over the pixels (unbiased), while
// a fixed offset of ½ gives every ray 137. Early termination stops a ray at the first sample
// past 0.995: its opacity lies in (0.995, 0.995 + 0.005·α′], α′ the step's opacity.
class VolumeClosedForm : public VolumeTest {
 protected:
  struct Ray {
    FloatImage opacity;
    Rgba8Image color;
  };
  Ray render(float alpha, float sampleDistance, bool jitter) {
    // Uniform but for one corner voxel (a value range for the table); the table is constant.
    const fs::path file = volume("slab", kN, 1.0f, [](glm::vec3 p) {
      return p.x < -0.99f && p.y < -0.99f && p.z < -0.99f ? 0.0f : 1.0f;
    });
    const std::string a = std::to_string(alpha);
    const Scene s =
        alongZ(R"({"name": "slab", "file": ")" + file.string() +
               R"(", "shading": false, "opacityDistance": 1, "sampleDistance": )" +
               std::to_string(sampleDistance) + R"(, "jitter": )" + (jitter ? "true" : "false") +
               R"(, "transferFunction": [{"value": 0, "color": [1, 1, 1], "opacity": )" + a +
               R"(}, {"value": 1, "color": [1, 1, 1], "opacity": )" + a + R"(}]})");
    Renderer renderer(s, test::glContext().info());
    renderer.render();
    return {aov(renderer.readAovs(), "volumeOpacity"), renderer.readColor()};
  }
  static constexpr int kN = 41;  // voxels a side: spacing 0.05, L = 2.05
};

TEST_F(VolumeClosedForm, AUniformBoxKeepsTheTransmittanceOfItsDepth) {
  const double alpha = 0.05, expected = 1.0 - std::pow(1.0 - alpha, kN);  // L/s = 41 voxels
  for (const bool jitter : {false, true}) {
    const Ray ray = render(float(alpha), 0.5f, jitter);
    double worstOpacity = 0.0, worstColor = 0.0;
    for (int y = 0; y < 96; ++y)
      for (int x = 0; x < 96; ++x) {
        worstOpacity = std::max(worstOpacity, std::abs(ray.opacity.at(x, y)[0] - expected));
        worstColor = std::max(worstColor, std::abs(ray.color.at(x, y)[0] - 255.0 * expected));
      }
    std::printf("uniform box, jitter %d: opacity %.5f, worst %.2e; colour worst %.2f levels\n",
                jitter, expected, worstOpacity, worstColor);
    EXPECT_LE(worstOpacity, 1e-4);
    EXPECT_LE(worstColor, 1.0);
  }
}

// A label volume (Burns11 §7.1) in three bands along x, labels 1, 2 and 3; 1 and 2 listed
// with their own colour and opacity, 3 not (clear). Seen along z, each ray stays in one band,
// so each pixel is the uniform box's closed form for its label: opacity 1 − (1 − α)^41,
// colour the label's colour times it; the unlisted band clear.
TEST_F(VolumeClosedForm, ALabelVolumesBandsAreEachTheirMaterialsClosedForm) {
  const fs::path file = volume("bands", kN, 1.0f, [](glm::vec3 p) {
    return p.x < -0.25f ? 1.0f : p.x < 0.25f ? 2.0f : 3.0f;
  });
  const Scene s = alongZ(R"({"name": "bands", "file": ")" + file.string() +
                         R"(", "labels": true, "shading": false, "opacityDistance": 1,
                         "sampleDistance": 0.5, "transferFunction": [
                           {"value": 1, "color": [1, 0, 0], "opacity": 0.05},
                           {"value": 2, "color": [0, 1, 0], "opacity": 0.1}]})");
  Renderer renderer(s, test::glContext().info());
  renderer.render();
  const FloatImage opacity = aov(renderer.readAovs(), "volumeOpacity");
  const Rgba8Image color = renderer.readColor();
  const double expected[3] = {1.0 - std::pow(0.95, kN), 1.0 - std::pow(0.9, kN), 0.0};
  int counted[3] = {0, 0, 0};
  test::Mismatches wrongOpacity, wrongColor;  // opacity; the label's channel in levels
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const float wx = (x + 0.5f) / float(s.width) * 1.6f - 0.8f;  // the view is 1.6 wide
      if (std::abs(std::abs(wx) - 0.25f) < 0.1f) continue;         // near a band's edge
      const int band = wx < -0.25f ? 0 : wx < 0.25f ? 1 : 2;
      ++counted[band];
      const double o = opacity.at(x, y)[0], want = expected[band];
      if (std::abs(o - want) > 1e-4) wrongOpacity.add(x, y, want, o);
      const int channel = band == 2 ? 0 : band;  // red, green; the clear band: all black
      if (std::abs(color.at(x, y)[channel] - 255.0 * want) > 1.0)
        wrongColor.add(x, y, 255.0 * want, color.at(x, y)[channel]);
    }
  for (int band = 0; band < 3; ++band) EXPECT_GT(counted[band], 500) << band;
  EXPECT_EQ(wrongOpacity.count(), 0) << wrongOpacity;
  EXPECT_EQ(wrongColor.count(), 0) << wrongColor;
}

// A mesh inside a volume stops its rays: a plane at z = 0 (scaled to 0.02 of its 20 units:
// x, y in [−0.2, 0.2]) in the uniform box seen along z. A ray onto the plane crosses only the
// box's front half, L/2 = 20.5 voxels, so it keeps T = (1 − α)^20.5; the rays beside it the
// whole depth, (1 − α)^41.
TEST_F(VolumeClosedForm, AMeshInsideStopsTheRaysAtItsDepth) {
  const double alpha = 0.05;
  const fs::path file = volume("slab", kN, 1.0f, [](glm::vec3 p) {
    return p.x < -0.99f && p.y < -0.99f && p.z < -0.99f ? 0.0f : 1.0f;
  });
  const Scene s =
      parseScene(R"({"resolution": [96, 96], "samples": 1, "background": [0, 0, 0],
      "style": {"name": "gooch", "lines": false},
      "camera": {"projection": "orthographic", "height": 1.6, "eye": [0, 0, 4], "target": [0, 0, 0]},
      "objects": [{"name": "plane", "file": ")" +
                     kData + R"(/render/plane.obj", "transform": {"scale": 0.02}}],
      "volumes": [{"name": "slab", "file": ")" +
                     file.string() +
                     R"(", "shading": false, "opacityDistance": 1, "sampleDistance": 0.5,
                   "jitter": false, "transferFunction": [{"value": 0, "opacity": 0.05},
                   {"value": 1, "opacity": 0.05}]}]})",
                 "mesh-in-volume.json", dir_);
  const auto aovs = renderAovs(s);
  const FloatImage &opacity = aov(aovs, "volumeOpacity"), &ids = aov(aovs, "objectId");
  const double onPlane = 1.0 - std::pow(1.0 - alpha, 20.5),
               beside = 1.0 - std::pow(1.0 - alpha, kN);
  int planePixels = 0;
  test::Mismatches wrong;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const bool plane = ids.at(x, y)[0] == 0.0f;
      planePixels += plane;
      const double want = plane ? onPlane : beside;
      if (std::abs(opacity.at(x, y)[0] - want) > 1e-4) wrong.add(x, y, want, opacity.at(x, y)[0]);
    }
  std::printf("mesh in a volume: %d pixels on the plane, opacity %.5f there, %.5f beside\n",
              planePixels, onPlane, beside);
  EXPECT_GT(planePixels, 500);  // 24 × 24
  EXPECT_EQ(wrong.count(), 0) << wrong;
}

TEST_F(VolumeClosedForm, JitteredStartsTakeLOverHSamplesOnAverage) {
  const double alpha = 0.05, sampleDistance = 0.3, L = kN * 0.05, h = sampleDistance * 0.05;
  const double stepAlpha = 1.0 - std::pow(1.0 - alpha, sampleDistance);  // opacityDistance 1
  for (const bool jitter : {false, true}) {
    const FloatImage opacity = render(float(alpha), float(sampleDistance), jitter).opacity;
    double sum = 0.0, worstInteger = 0.0;
    int lower = 0;
    for (float a : opacity.data) {
      const double samples = std::log(1.0 - a) / std::log(1.0 - stepAlpha);
      sum += samples;
      worstInteger = std::max(worstInteger, std::abs(samples - std::round(samples)));
      lower += std::lround(samples) == std::lround(std::floor(L / h));
    }
    const double mean = sum / double(opacity.data.size());
    std::printf("jitter %d: %.4f samples per ray on average (L/h = %.4f), %d rays of %ld\n", jitter,
                mean, L / h, lower, std::lround(std::floor(L / h)));
    EXPECT_LE(worstInteger, 0.02);  // each ray a whole number of samples
    if (jitter)
      EXPECT_NEAR(mean, L / h, 0.05);
    else
      EXPECT_NEAR(mean, std::ceil(L / h - 0.5), 0.02);
  }
}

TEST_F(VolumeClosedForm, EarlyTerminationStopsAtTheFirstSamplePastTheThreshold) {
  const double alpha = 0.3, stepAlpha = 1.0 - std::pow(1.0 - alpha, 0.5);
  const Ray ray = render(float(alpha), 0.5f, true);
  float least = 1.0f, most = 0.0f;
  for (float a : ray.opacity.data) least = std::min(least, a), most = std::max(most, a);
  std::printf("early termination: opacity in [%.6f, %.6f], bound (0.995, %.6f]; exact %.7f\n",
              least, most, 0.995 + 0.005 * stepAlpha, 1.0 - std::pow(1.0 - alpha, kN));
  EXPECT_GT(least, 0.995f);
  EXPECT_LE(most, 0.995 + 0.005 * stepAlpha + 1e-6);
}

// A volume larger than the GPU's 3-D textures on one axis is refused when the renderer is
// made, naming the scene's place, the volume's file and the limit.
TEST_F(VolumeTest, AVolumeBeyondTheGpusTextureSizeIsRefused) {
  test::glContext();  // current, for the query
  GLint maxSize = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &maxSize);
  ASSERT_GT(maxSize, 0);
  const int n = maxSize + 1;
  std::ofstream(dir_ / "long.raw", std::ios::binary)
      .write(std::vector<char>(std::size_t(n) * 4, 0).data(), std::streamsize(n) * 4);
  std::ofstream(dir_ / "long.json")
      << R"({"file": "long.raw", "dims": [)" << n << R"(, 1, 1], "type": "f32"})";
  const Scene s = scene(R"({"name": "long", "file": ")" + (dir_ / "long.json").string() +
                        R"(", "transferFunction": [{"value": 0, "opacity": 1}]})");
  expectError([&] { Renderer renderer(s, test::glContext().info()); },
              {"/volumes/0/file", "long.json", std::to_string(n) + "×1×1",
               "3-D texture size of " + std::to_string(maxSize)});
}

// A label volume's table holds a texel per label of its transfer function's span and a clear
// one at each end: a span the GPU's 2-D texture size allows draws its labels, one more is
// refused at the transfer function (it sampled as black).
TEST_F(VolumeTest, ALabelSpanBeyondTheGpusTextureSizeIsRefused) {
  test::glContext();  // current, for the query
  GLint maxSize = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  ASSERT_GT(maxSize, 2);
  for (const int last : {maxSize - 2, maxSize - 1}) {
    SCOPED_TRACE(last);
    const fs::path file =
        volume("span", 8, 1.0f, [&](glm::vec3 p) { return p.x < 0.0f ? 1.0f : float(last); });
    const Scene s = scene(R"({"name": "span", "file": ")" + file.string() +
                          R"(", "labels": true, "shading": false, "transferFunction": [
                            {"value": 1, "color": [1, 0, 0], "opacity": 1},
                            {"value": )" +
                          std::to_string(last) + R"(, "color": [0, 0, 1], "opacity": 1}]})");
    if (last == maxSize - 1) {
      expectError(
          [&] { Renderer renderer(s, test::glContext().info()); },
          {"/volumes/0/transferFunction", "its labels span " + std::to_string(last) + " values",
           "2-D texture size of " + std::to_string(maxSize)});
      continue;
    }
    Renderer renderer(s, test::glContext().info());
    renderer.render();
    const Rgba8Image color = renderer.readColor();
    int red = 0, blue = 0;
    for (std::size_t i = 0; i + 3 < color.pixels.size(); i += 4) {
      red += color.pixels[i] > 200 && color.pixels[i + 2] < 50;
      blue += color.pixels[i + 2] > 200 && color.pixels[i] < 50;
    }
    EXPECT_GT(red, 300);
    EXPECT_GT(blue, 300);
  }
}

namespace {

// The volume AOVs and the colour (emission only over black) of scene `s` as the CPU reference
// casts them, pixel by pixel; the volume covering at least `covering` of the picture.
void expectCastAsCpu(const Scene& s, float covering = 0.25f) {
  Renderer renderer(s, test::glContext().info());
  renderer.render();
  const auto aovs = renderer.readAovs();
  const Rgba8Image color = renderer.readColor();
  const FloatImage &opacity = aov(aovs, "volumeOpacity"), &entry = aov(aovs, "volumeEntryDepth"),
                   &hit = aov(aovs, "volumeHitDepth");
  const Camera c = s.resolvedCamera();
  const float aspect = float(s.width) / float(s.height);
  const SceneVolume& v = s.volumes[0];
  const float step = v.sampleDistance * 2.0f / float(v.volume->dims.x - 1);
  const bool maximum = v.mode == VolumeMode::Maximum;
  int covered = 0, opaque = 0;
  double colorError = 0.0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const VolumeRay cpu = castVolumeRay(v, c.view(), c.projectionMatrix(aspect),
                                          {s.width, s.height}, {x, s.height - 1 - y});
      EXPECT_EQ(std::isnan(entry.at(x, y)[0]), std::isnan(cpu.entryDepth)) << x << "," << y;
      if (std::isnan(cpu.entryDepth)) continue;
      ++covered;
      EXPECT_NEAR(entry.at(x, y)[0], cpu.entryDepth, 1e-3f) << x << "," << y;
      // The GPU's transfer table (1024 texels) and filtering weights against exact ones.
      EXPECT_NEAR(opacity.at(x, y)[0], cpu.opacity, 0.01f) << x << "," << y;
      // Composite: where the opacity clearly passes ½; maximum: wherever there is one.
      if (!std::isnan(cpu.hitDepth) && cpu.opacity > (maximum ? 0.01f : 0.55f)) {
        ++opaque;
        EXPECT_NEAR(hit.at(x, y)[0], cpu.hitDepth, 2.0f * step) << x << "," << y;
      }
      const std::uint8_t* rgb = &color.pixels[(std::size_t(y) * s.width + x) * 4];
      for (int k = 0; k < 3; ++k) {
        const float e = std::abs(rgb[k] / 255.0f - cpu.color[k]);
        colorError = std::max(colorError, double(e));
      }
    }
  EXPECT_LT(colorError, 0.02) << "largest colour difference";
  EXPECT_GT(covered, covering * float(s.width * s.height));
  EXPECT_GT(opaque, 0);
}

// A blob: a Gaussian off centre with a ripple, so values and gradient magnitudes both vary.
float blob(glm::vec3 p) {
  return std::exp(-2.0f * glm::dot(p - glm::vec3(0.2f, 0, 0), p - glm::vec3(0.2f, 0, 0))) +
         0.3f * std::sin(4.0f * p.y) * std::exp(-glm::dot(p, p));
}

}  // namespace

// Composite and maximum modes.
class VolumeModes : public VolumeTest, public ::testing::WithParamInterface<const char*> {};

TEST_P(VolumeModes, TheGpuCastsWhatTheCpuReferenceCasts) {
  const fs::path file = volume("blob", 32, 1.0f, blob);
  expectCastAsCpu(scene(R"({"name": "blob", "file": ")" + file.string() + R"(", "mode": ")" +
                        GetParam() + R"(", "shading": false, )" + kRamp + "}"));
}

// Empty-space skipping against a march of every sample: two small balls in a 48³ volume of
// zeros (under the ramp, opacity 0) leave most of its 8³-voxel blocks empty, which the GPU's
// rays skip; the CPU reference marches every sample and must see the same picture.
TEST_P(VolumeModes, SkippingEmptyBlocksChangesNothing) {
  const fs::path file = volume("sparse", 48, 1.0f, [](glm::vec3 p) {
    const float a = 0.35f - glm::distance(p, glm::vec3(-0.45f, 0.3f, 0.1f));
    const float b = 0.25f - glm::distance(p, glm::vec3(0.5f, -0.4f, -0.3f));
    return std::clamp(4.0f * std::max(a, b), 0.0f, 1.0f);
  });
  expectCastAsCpu(scene(R"({"name": "sparse", "file": ")" + file.string() + R"(", "mode": ")" +
                        GetParam() + R"(", "shading": false, )" + kRamp + "}"),
                  0.04f);
}

INSTANTIATE_TEST_SUITE_P(Modes, VolumeModes, ::testing::Values("composite", "maximum"));

TEST(TransferFunction, TwoDimensionalInterpolatesBetweenRowsAndHoldsBeyondThem) {
  TransferFunction tf;
  tf.rows = {{1.0f, {{0.0f, {1, 0, 0}, 0.0f, 0.0f}, {2.0f, {1, 0, 0}, 0.4f, 1.0f}}},
             {3.0f, {{1.0f, {0, 0, 1}, 0.8f, 0.5f}}}};
  // Halfway between the rows at value 1: row 1 gives 0.2, row 2 (one point) 0.8.
  EXPECT_FLOAT_EQ(tf.at(1.0f, 2.0f).opacity, 0.5f);
  EXPECT_FLOAT_EQ(tf.at(1.0f, 2.5f).color.b, 0.75f);
  EXPECT_FLOAT_EQ(tf.at(1.0f, 2.5f).importance, 0.5f);
  EXPECT_FLOAT_EQ(tf.at(2.0f, 0.0f).opacity, 0.4f);  // below the first row: the first
  EXPECT_FLOAT_EQ(tf.at(-4.0f, 9.0f).opacity, 0.8f);  // beyond the last: the last
  EXPECT_FLOAT_EQ(tf.maxOpacity(0.0f), 0.8f);
  TransferFunction clear;
  clear.rows = {{0.0f, {{0.0f, {1, 1, 1}, 0.0f, 0.5f}, {1.0f, {1, 1, 1}, 0.0f, 0.5f},
                        {2.0f, {1, 1, 1}, 0.3f, 0.5f}}},
                {5.0f, {{0.0f, {1, 1, 1}, 0.0f, 0.5f}}}};
  EXPECT_FALSE(clear.opaqueSomewhere(-1.0f, 1.0f));
  EXPECT_TRUE(clear.opaqueSomewhere(-1.0f, 1.5f));
}

// The gradient the two-dimensional transfer function reads: the voxels' central differences,
// interpolated and taken to world units, against the analytic gradient of the sampled field
// (central differences are exact to O(h²)).
TEST_F(VolumeTest, TheInterpolatedGradientIsTheSampledFieldsGradient) {
  const auto f = [](glm::vec3 p) { return std::exp(-2.0f * glm::dot(p, p)); };
  const fs::path file = volume("gauss", 48, 1.0f, f);
  const Scene s = scene(R"({"name": "g", "file": ")" + file.string() +
                        R"(", "transferFunction": [{"value": 0, "opacity": 0.1}]})");
  const SceneVolume& v = s.volumes[0];
  const glm::mat4 worldToIndex = glm::inverse(v.indexToWorld());
  const glm::mat3 toWorld = glm::transpose(glm::mat3(worldToIndex));
  const float h = 2.0f / 47.0f;
  double worst = 0.0;
  for (int n = 0; n < 200; ++n) {
    // Points on a spiral inside the box, off the voxel centres.
    const float a = 0.37f * float(n), r = 0.8f * float(n) / 200.0f;
    const glm::vec3 p(r * std::cos(a), r * std::sin(a), 0.6f * std::sin(0.11f * float(n)));
    const glm::vec3 analytic = -4.0f * p * f(p);
    const glm::vec3 index = glm::vec3(worldToIndex * glm::vec4(p, 1.0f));
    const glm::vec3 g = toWorld * sampleGradient(*v.volume, index);
    worst = std::max(worst, double(glm::length(g - analytic)));
  }
  // |∂³f| ≤ ~20 here: central differences err by h²/6·20, interpolation by h²/8·|∂²∇f|.
  EXPECT_LT(worst, 12.0 * h * h) << "largest gradient error";
}

// A two-dimensional transfer function (value × gradient magnitude): the GPU casts what the CPU
// reference casts, and the gradient rows matter (the first row alone casts another image).
TEST_F(VolumeTest, ATwoDimensionalTransferFunctionCastsAsTheCpuReference) {
  const fs::path file = volume("blob", 32, 1.0f, blob);
  const std::string rows = R"("transferFunction2D": [
      {"gradient": 0.2, "points": [{"value": 0.2, "color": [0.2, 0.4, 1.0], "opacity": 0.0},
                                   {"value": 1.0, "color": [0.2, 0.4, 1.0], "opacity": 0.05}]},
      {"gradient": 1.0, "points": [{"value": 0.1, "color": [1.0, 0.5, 0.1], "opacity": 0.0},
                                   {"value": 0.4, "color": [1.0, 0.5, 0.1], "opacity": 0.4}]}])";
  const std::string head = R"({"name": "blob", "file": ")" + file.string() + R"(", "shading": false, )";
  for (const char* mode : {"composite", "maximum"}) {
    SCOPED_TRACE(mode);
    expectCastAsCpu(scene(head + R"("mode": ")" + mode + R"(", )" + rows + "}"));
  }
  const Scene twoD = scene(head + rows + "}");
  Scene firstRow = twoD;
  firstRow.volumes[0].transfer.rows.resize(1);
  const auto a = renderAovs(twoD), b = renderAovs(firstRow);
  const FloatImage &withRows = aov(a, "volumeOpacity"), &without = aov(b, "volumeOpacity");
  float largest = 0.0f;
  for (int y = 0; y < twoD.height; ++y)
    for (int x = 0; x < twoD.width; ++x)
      largest = std::max(largest, std::abs(withRows.at(x, y)[0] - without.at(x, y)[0]));
  EXPECT_GT(largest, 0.2f);
}

// The viewer edits a transfer function between frames: the next frame of the same renderer
// draws what a renderer made for the edited scene draws (table, empty-space blocks, the
// volume of interest's seed, a label volume's gradient).
TEST_F(VolumeTest, AnEditedTransferFunctionIsDrawnByTheNextFrame) {
  const fs::path file = volume("blob", 32, 1.0f, blob);
  Scene s = scene(R"({"name": "blob", "file": ")" + file.string() + R"(", )" + kRamp + "}");
  Renderer live(s, test::glContext().info());
  live.render();
  const Rgba8Image before = live.readColor();
  std::vector<TransferPoint>& points = s.volumes[0].transfer.rows.front().points;
  points[1].opacity = 0.0f;  // the middle values turn clear: blocks of them empty
  points[2].color = {0.1f, 0.9f, 0.2f};
  points.push_back({1.2f, {1.0f, 0.0f, 0.0f}, 0.5f, 1.0f});
  live.render();
  const Rgba8Image edited = live.readColor();
  Renderer fresh(s, test::glContext().info());
  fresh.render();
  EXPECT_EQ(edited.pixels, fresh.readColor().pixels);
  EXPECT_NE(edited.pixels, before.pixels);
}

// Shadows of a volume's material (Beer–Lambert towards the key light): a translucent slab
// over a block, lit and seen from straight above. At each pixel's hit on the block, the
// volumeLightTransmittance AOV against the transmittance integrated finely along the vertical
// through the interpolated field, exactly per the transfer function; the GPU's shadow ray
// takes a step of one voxel, so the tolerance is one step's absorption of the slab. Where a
// box cut removes the slab, the light falls into the cut.
TEST_F(VolumeTest, AVolumesShadowIsTheBeerLambertTransmittanceTowardsTheLight) {
  const float slab = 0.5f, block = 1.0f, alpha = 0.12f;
  const fs::path file = volume("shelf", 40, 1.0f, [&](glm::vec3 p) {
    if (p.y < -0.3f) return block;
    return std::abs(p.x) < 0.6f && std::abs(p.z) < 0.6f && p.y > 0.2f && p.y < 0.45f ? slab : 0.0f;
  });
  const std::string tf = R"("transferFunction": [{"value": 0, "opacity": 0},
      {"value": 0.5, "opacity": )" +
                         std::to_string(alpha) + R"(}, {"value": 1, "opacity": 0.6}])";
  const std::string rest = R"(, "lights": [{"type": "directional", "direction": [0, -1, 0],
      "space": "world"}])";
  for (const bool cut : {false, true}) {
    SCOPED_TRACE(cut ? "slab cut open for x < 0" : "whole slab");
    Scene s = scene(R"({"name": "shelf", "file": ")" + file.string() +
                        R"(", "shadows": true, "jitter": false, )" + tf + "}",
                    rest + (cut ? R"(, "cutters": {"boxCut": {"center": [-1, 0.3, 0],
                                     "size": [2, 0.6, 3]}})"
                                : ""));
    s.camera.fit = false;
    s.camera.projection = Projection::Orthographic;
    s.camera.eye = {0.0f, 4.0f, 0.0f};
    s.camera.target = {0.0f, 0.0f, 0.0f};
    s.camera.up = {0.0f, 0.0f, -1.0f};
    s.camera.height = 2.4f;
    const auto aovs = renderAovs(s);
    const FloatImage &light = aov(aovs, "volumeLightTransmittance"),
                     &hit = aov(aovs, "volumeHitDepth");
    const Camera c = s.resolvedCamera();
    const glm::mat4 inverse =
        glm::inverse(c.projectionMatrix(float(s.width) / s.height) * c.view());
    const SceneVolume& v = s.volumes[0];
    const glm::mat4 worldToIndex = glm::inverse(v.indexToWorld());
    const float voxel = 2.0f / 39.0f;
    const auto removed = [&](glm::vec3 p) { return cut && p.x < 0.0f && p.y > 0.0f; };
    int shadowed = 0, lit = 0;
    for (int y = 0; y < s.height; ++y)
      for (int x = 0; x < s.width; ++x) {
        const float depth = hit.at(x, y)[0];
        if (std::isnan(depth)) continue;
        const glm::vec2 uv((x + 0.5f) / s.width, 1.0f - (y + 0.5f) / s.height);
        const glm::vec4 near = inverse * glm::vec4(uv * 2.0f - 1.0f, -1.0f, 1.0f);
        glm::vec3 p = glm::vec3(near) / near.w;
        p.y = 4.0f - depth;
        // Away from the slab's and the cut's edges, where a voxel decides.
        if (std::abs(std::abs(p.x) - 0.6f) < 2 * voxel ||
            std::abs(std::abs(p.z) - 0.6f) < 2 * voxel || (cut && std::abs(p.x) < 2 * voxel) ||
            std::abs(p.x) > 0.9f || std::abs(p.z) > 0.9f)
          continue;
        double opticalDepth = 0.0;  // in units of the opacity distance (one voxel)
        const float dt = 0.01f * voxel;
        // The GPU's first sample, one voxel up, stands for the voxel around it.
        for (float t = 0.5f * voxel; p.y + t < 1.0f + 0.5f * voxel; t += dt) {
          const glm::vec3 q = p + glm::vec3(0.0f, t, 0.0f);
          if (removed(q)) continue;
          const float value = sampleVolume(*v.volume, glm::vec3(worldToIndex * glm::vec4(q, 1.0f)));
          opticalDepth -= std::log(1.0 - v.material(value).opacity) * dt / voxel;
        }
        const double expected = std::exp(-opticalDepth);
        const double tolerance = -std::log(1.0 - alpha) * 1.0 + 0.02;  // one step of the slab
        EXPECT_NEAR(std::log(light.at(x, y)[0]), std::log(expected), tolerance)
            << x << "," << y << " at " << p.x << ", " << p.z;
        (std::abs(p.x) < 0.6f && std::abs(p.z) < 0.6f && !removed({p.x, 0.3f, p.z}) ? shadowed
                                                                                    : lit)++;
      }
    EXPECT_GT(shadowed, cut ? 100 : 200);
    EXPECT_GT(lit, 200);
  }
}

// The faces a box cut leaves on a solid block all face a light that shines into the cut,
// which holds no material: each is lit whole. A face's samples lie up to a step inside the
// kept material, and the shadow ray from there met that material first where the light
// grazes the face (bands of shadow on the face, by the sample lattice's phase).
TEST_F(VolumeTest, ACutsFacesLitThroughTheCutHaveNoShadowBands) {
  const fs::path file = volume("block", 48, 1.0f, [](glm::vec3 p) {
    return glm::all(glm::lessThan(glm::abs(p), glm::vec3(0.85f))) ? 1.0f : 0.0f;
  });
  Scene s =
      scene(R"({"name": "block", "file": ")" + file.string() +
                R"(", "shadows": true, "jitter": false,
                  "transferFunction": [{"value": 0, "opacity": 0}, {"value": 1, "opacity": 0.9}]})",
            R"(, "lights": [{"type": "directional", "direction": [-1, -2, -0.5], "space": "world"}],
                  "cutters": {"boxCut": {"center": [1, 1, 1], "size": [2, 2, 2]}})");
  s.width = 192, s.height = 144;
  s.camera.eye = {2.6f, 2.0f, 3.0f};
  const auto aovs = renderAovs(s);
  const FloatImage &light = aov(aovs, "volumeLightTransmittance"),
                   &hit = aov(aovs, "volumeHitDepth");
  const Camera c = s.resolvedCamera();
  const glm::mat4 inverse = glm::inverse(c.projectionMatrix(float(s.width) / s.height) * c.view());
  int faces = 0, shadowed = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      if (std::isnan(hit.at(x, y)[0])) continue;
      const glm::vec3 d = pixelRay(inverse, {(x + 0.5f) / s.width, 1.0f - (y + 0.5f) / s.height}).d;
      const glm::vec3 p =
          c.eye + hit.at(x, y)[0] / glm::dot(d, glm::normalize(c.target - c.eye)) * d;
      // On one of the cut's three faces (one coordinate ≈ 0), away from the edges between them
      // and from the block's rim.
      int on = 0, inside = 0;
      for (int k = 0; k < 3; ++k) {
        on += std::abs(p[k]) < 0.05f;
        inside += p[k] > 0.12f && p[k] < 0.75f;
      }
      if (on != 1 || inside != 2) continue;
      ++faces;
      shadowed += light.at(x, y)[0] < 0.9f;
    }
  EXPECT_GT(faces, 1500);
  EXPECT_EQ(shadowed, 0) << "of " << faces;
}

// A mesh inside the volume stops the rays: in front of it the volume is cast up to its depth,
// exactly as the CPU reference casts it with that depth.
TEST_F(VolumeTest, AMeshInsideTheVolumeStopsTheRays) {
  const fs::path file = volume("fog", 24, 1.0f, [](glm::vec3) { return 1.0f; });
  const std::string tf =
      R"("transferFunction": [{"value": 0, "opacity": 0}, {"value": 1, "opacity": 0.05}])";
  Scene s = scene(
      R"({"name": "fog", "file": ")" + file.string() + R"(", "shading": false, )" + tf + "}",
      R"(, "objects": [{"name": "core", "file": ")" + kData +
          R"(/meshes/cube.obj", "transform": {"translate": [-0.3, -0.3, -0.3], "scale": 0.6}}])");
  const auto aovs = renderAovs(s);
  const FloatImage &opacity = aov(aovs, "volumeOpacity"), &depth = aov(aovs, "depth"),
                   &ids = aov(aovs, "objectId");
  const Camera c = s.resolvedCamera();
  const float aspect = float(s.width) / float(s.height);
  int onMesh = 0;
  double blocked = 0.0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const glm::ivec2 p(x, s.height - 1 - y);
      const VolumeRay cpu = castVolumeRay(s.volumes[0], c.view(), c.projectionMatrix(aspect),
                                          {s.width, s.height}, p, depth.at(x, y)[0]);
      EXPECT_NEAR(opacity.at(x, y)[0], cpu.opacity, 0.01f) << x << "," << y;
      if (ids.at(x, y)[0] != 0.0f) continue;
      ++onMesh;
      const VolumeRay through =
          castVolumeRay(s.volumes[0], c.view(), c.projectionMatrix(aspect), {s.width, s.height}, p);
      blocked += through.opacity - opacity.at(x, y)[0];
    }
  EXPECT_GT(onMesh, 200);
  EXPECT_GT(blocked / onMesh, 0.1) << "the fog behind the core is not drawn over it";
}

namespace {

// Scene `s`'s volume AOVs on the GPU against the CPU reference whose samples `keep` decides,
// within the tolerances; counts the pixels compared and those whose entry the cut moved more
// than `deeperBy` behind the uncut volume's.
struct CutAgreement {
  int compared = 0, deeper = 0;
};
CutAgreement expectCutAsCpu(const Scene& s, const std::function<bool(const glm::vec3&)>& keep,
                            float entryTolerance, float opacityTolerance, float deeperBy) {
  const auto aovs = renderAovs(s);
  const FloatImage &opacity = aov(aovs, "volumeOpacity"), &entry = aov(aovs, "volumeEntryDepth");
  const Camera c = s.resolvedCamera();
  const glm::mat4 view = c.view(), projection = c.projectionMatrix(float(s.width) / s.height);
  CutAgreement a;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const glm::ivec2 p(x, s.height - 1 - y), size(s.width, s.height);
      const VolumeRay cut = castVolumeRay(s.volumes[0], view, projection, size, p, 1.0f, keep);
      const VolumeRay whole = castVolumeRay(s.volumes[0], view, projection, size, p);
      EXPECT_EQ(std::isnan(entry.at(x, y)[0]), std::isnan(cut.entryDepth)) << x << "," << y;
      if (std::isnan(cut.entryDepth) || std::isnan(entry.at(x, y)[0])) continue;
      ++a.compared;
      EXPECT_NEAR(entry.at(x, y)[0], cut.entryDepth, entryTolerance) << x << "," << y;
      EXPECT_NEAR(opacity.at(x, y)[0], cut.opacity, opacityTolerance) << x << "," << y;
      if (cut.entryDepth > whole.entryDepth + deeperBy) ++a.deeper;
    }
  return a;
}

}  // namespace

// The box cut removes ray samples where its C++ mirror says, and rays entering the block
// through the cut show its face.
TEST_F(VolumeTest, TheBoxCutDecidesRaySamplesAsItsCppMirror) {
  const fs::path file = volume("solid", 24, 1.0f, [](glm::vec3 p) { return 0.6f + 0.4f * p.x; });
  Scene s = scene(
      R"({"name": "solid", "file": ")" + file.string() + R"(", "shading": false, )" + kRamp + "}",
      R"(, "cutters": {"boxCut": {"center": [0.6, 0.6, 0.8], "size": [1.4, 1.4, 1.4],
                       "rotate": [0, 20, 0]}})");
  const BoxCutOptions& box = *s.cutters.find<BoxCutOptions>();
  const Camera c = s.resolvedCamera();
  const CutAgreement a = expectCutAsCpu(
      s,
      [&](const glm::vec3& p) {
        return boxCutFragment(box, p, true, c.rayOrigin(p)).fate != BoxCutFate::Fate::Discard;
      },
      1e-3f, 0.01f, 0.05f);
  EXPECT_GT(a.deeper, 200) << "the box opens the volume";
}

// Diepstraten03 on an exterior volume: the wedge lies on the main axis of its material (rule
// 3: here a slab long along z inside a cubic grid), faces the viewer, and removes the ray
// samples its C++ mirror says, jitter included; rays entering through the cut show the wall.
TEST_F(VolumeTest, TheCutoutWedgeLiesOnTheMaterialsMainAxisAndDecidesRaySamples) {
  const fs::path file = volume("slab", 32, 1.0f, [](glm::vec3 p) {
    return std::abs(p.x) < 0.45f && std::abs(p.y) < 0.3f && std::abs(p.z) < 0.9f ? 0.8f : 0.0f;
  });
  Scene s = scene(R"({"name": "slab", "role": "exterior", "file": ")" + file.string() +
                      R"(", "shading": false, )" + kRamp + "}",
                  R"(, "cutters": {"cutout": {"angle": 70,
                       "jitter": {"pattern": "sawtooth", "amplitude": 0.02, "frequency": 6}}})");
  const std::vector<ExteriorUnit> units = exteriorUnits(s);
  ASSERT_EQ(units.size(), 1u);
  EXPECT_EQ(units[0].volumes, std::vector<std::size_t>{0});
  EXPECT_GT(std::abs(units[0].axes.axes[0].z), 0.999f) << "the main axis runs along the slab";
  // The hull of the material's voxel centres: z from −0.871 to 0.871 (spacing 2/31).
  EXPECT_NEAR(units[0].axes.extentMax - units[0].axes.extentMin, 2 * 27 / 31.0f, 1e-4f);

  const Camera c = s.resolvedCamera();
  const CutoutOptions& options = *s.cutters.find<CutoutOptions>();
  const CutoutWedge wedge = cutoutWedge(units[0].axes, options, c.eye - units[0].axes.center);
  const CutAgreement a = expectCutAsCpu(
      s, [&](const glm::vec3& p) { return cutoutDistance(wedge, options.jitter, p) <= 0.0f; },
      1e-3f, 0.01f, 0.05f);
  EXPECT_GT(a.compared, 500);
  EXPECT_GT(a.deeper, 150) << "the wedge opens the slab";
}

// Trapp13's clip surface with a relief removes ray samples where its C++ mirror says; a ray
// entering the volume through the cut shows its face, lit by the relief's normal.
TEST_F(VolumeTest, AClipSurfaceDecidesRaySamplesAsItsCppMirror) {
  const fs::path file = volume("solid", 24, 1.0f, [](glm::vec3 p) { return 0.6f + 0.4f * p.y; });
  Scene s = scene(
      R"({"name": "solid", "file": ")" + file.string() + R"(", "shading": false, )" + kRamp + "}",
      R"(, "cutters": {"clipSurfaces": {"surfaces": [
                       {"origin": [-2, -2, 0.2], "u": [0, 4, 0], "v": [4, 0, 0], "scale": [2, 2, 0.3],
                        "offsetMap": {"pattern": "noise", "frequency": 3, "octaves": 3, "size": 64}}]}})");
  const ClipSurfaceOptions& clip = *s.cutters.find<ClipSurfaceOptions>();
  // The relief is a texture on the GPU, bilinear over 64² texels: a sample within its
  // interpolation error of the surface may fall on the other side, moving the entry by a step.
  const CutAgreement a = expectCutAsCpu(
      s, [&](const glm::vec3& p) { return !clippedBySurfaces(clip, p); }, 0.05f, 0.02f, 0.1f);
  EXPECT_GT(a.compared, s.width * s.height / 4);
  EXPECT_GT(a.deeper, 200) << "the surface opens the volume";
}

// Burns11 §5.2.5: with an adaptive cutaway around an object of interest inside, the rays
// start at the cutaway surface, not before it.
TEST_F(VolumeTest, RaysStartAtTheAdaptiveCutawaySurface) {
  const fs::path file = volume("ct", 24, 1.0f, [](glm::vec3) { return 0.6f; });
  Scene s = scene(
      R"({"name": "ct", "file": ")" + file.string() + R"(", "shading": false, )" + kRamp + "}",
      R"(, "objects": [{"name": "probe", "file": ")" + kData +
          R"(/meshes/cube.obj", "role": "interest",
                      "transform": {"translate": [-0.25, -0.25, -0.25], "scale": 0.5}}],
                  "cutters": {"adaptive": {"angle": 35}})");
  const auto aovs = renderAovs(s);
  const FloatImage &entry = aov(aovs, "volumeEntryDepth"), &cutaway = aov(aovs, "cutawayDepth");
  const Camera c = s.resolvedCamera();
  const float aspect = float(s.width) / float(s.height);
  const glm::mat4 inverseProjection = glm::inverse(c.projectionMatrix(aspect));
  const float step = 0.5f * 2.0f / 23.0f;
  int opened = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const float e = entry.at(x, y)[0];
      // The cutaway buffer has a size of its own: sampled as the GLSL samples it (bilinear).
      const glm::vec2 texel((x + 0.5f) / s.width * cutaway.width - 0.5f,
                            (y + 0.5f) / s.height * cutaway.height - 0.5f);
      const glm::ivec2 base = glm::ivec2(glm::floor(texel));
      const glm::vec2 f = texel - glm::vec2(base);
      const auto at = [&](int i, int j) {
        return cutaway.at(std::clamp(base.x + i, 0, cutaway.width - 1),
                          std::clamp(base.y + j, 0, cutaway.height - 1))[0];
      };
      const float w =
          glm::mix(glm::mix(at(0, 0), at(1, 0), f.x), glm::mix(at(0, 1), at(1, 1), f.x), f.y);
      if (std::isnan(e) || !(w > 0.0f)) continue;
      const glm::vec2 uv((x + 0.5f) / s.width, 1.0f - (y + 0.5f) / s.height);
      const glm::vec4 h = inverseProjection * glm::vec4(uv * 2.0f - 1.0f, w * 2.0f - 1.0f, 1.0f);
      const float surface = -h.z / h.w;
      // The first kept sample lies behind the surface, by less than a step (plus the
      // surface's bilinear filtering between pixels).
      EXPECT_GE(e, surface - 0.02f) << x << "," << y;
      // Only where the volume begins in front of the surface (the cut opens it).
      const VolumeRay whole = castVolumeRay(s.volumes[0], c.view(), c.projectionMatrix(aspect),
                                            {s.width, s.height}, {x, s.height - 1 - y});
      if (!(whole.entryDepth < surface)) continue;
      ++opened;
      EXPECT_LE(e, surface + step + 0.02f) << x << "," << y;
    }
  EXPECT_GT(opened, 300);
}

// Burns11 §7.1: the contextual structure decides each ray sample by the importance of the
// sample's material (eqs. 7.1–7.3 with eq. 5.6's Ω). A block of one material around a cube of
// interest: the first kept sample along each ray lies where R(I, Ω) falls to ½, worked out here
// from the dumped C₁ and C₂: Ω* = (max(2I − 1, 0) + I)/2, at z₂ − 2Ω*(z₂ − z₁) when Ω* ≤ ½
// (transition region), at z₁ − (2Ω* − 1)d in front of C₁ when Ω* > ½ (overlay). Less important
// material (I = 0.3) is trimmed behind C₁, important material (I = 0.9) reaches into the
// overlay; within one step along the ray.
TEST_F(VolumeTest, TheContextualStructureTrimsEachMaterialWhereItsImportanceSays) {
  const float overlay = 0.3f, step = 0.5f * 2.0f / 23.0f;
  for (const float importance : {0.3f, 0.9f}) {
    SCOPED_TRACE(importance);
    const Scene s = contextualBlock(importance, "cut");
    const auto aovs = renderAovs(s);
    const FloatImage &entry = aov(aovs, "volumeEntryDepth"), &c1 = aov(aovs, "cutawayDepth"),
                     &c2 = aov(aovs, "cutawayDepthC2");
    const Camera c = s.resolvedCamera();
    const glm::mat4 projection = c.projectionMatrix(1.0f);
    const glm::mat4 inverseProjection = glm::inverse(projection);
    const auto distance = [&](float windowDepth) { return viewDistance(inverseProjection, windowDepth); };
    const float omega = 0.5f * (std::max(2.0f * importance - 1.0f, 0.0f) + importance);
    int trimmed = 0, inOverlay = 0;
    for (int y = 0; y < s.height; ++y)
      for (int x = 0; x < s.width; ++x) {
        const float e = entry.at(x, y)[0];
        if (std::isnan(e) || !(c1.at(x, y)[0] > 0.0f)) continue;
        const float z1 = distance(c1.at(x, y)[0]);
        const float z2 = std::max(distance(c2.at(x, y)[0]), z1);
        const float cut =
            omega <= 0.5f ? z2 - 2.0f * omega * (z2 - z1) : z1 - (2.0f * omega - 1.0f) * overlay;
        const VolumeRay whole = castVolumeRay(s.volumes[0], c.view(), projection,
                                              {s.width, s.height}, {x, s.height - 1 - y});
        EXPECT_GE(e, std::max(whole.entryDepth, cut) - 1e-3f) << x << "," << y;
        if (!(whole.entryDepth < cut)) continue;  // the volume begins behind the cut here
        EXPECT_LE(e, cut + step + 1e-3f) << x << "," << y;
        ++trimmed;
        inOverlay += cut < z1 - 0.05f;
      }
    EXPECT_GT(trimmed, 500);
    if (importance > 0.5f)
      EXPECT_GT(inOverlay, 300) << "important material stands in front of C₁";
    else
      EXPECT_EQ(inOverlay, 0);
  }
}

// Burns11 ch. 2 per volume sample: under the contextual structure applied as translucency
// (eq. 2.1) a sample's opacity is multiplied by 1 − R(I, Ω) instead of removing it. The block
// of one material (I = 0.3) around the cube of interest, jitter off: each pixel's accumulated
// opacity against the emission–absorption sum written out here over the same samples, each
// step's opacity 1 − (1 − α)^(Δs/d) times 1 − R, with Ω by eq. 5.6 from the dumped C₁, C₂ and
// R by eq. 7.3.
TEST_F(VolumeTest, AsTranslucencyRScalesEachSamplesOpacity) {
  const float overlay = 0.3f, importance = 0.3f, voxel = 2.0f / 23.0f, step = 0.5f * voxel;
  const Scene s = contextualBlock(importance, "translucency");
  const auto aovs = renderAovs(s);
  const FloatImage &opacity = aov(aovs, "volumeOpacity"), &c1 = aov(aovs, "cutawayDepth"),
                   &c2 = aov(aovs, "cutawayDepthC2");
  const Camera c = s.resolvedCamera();
  const glm::mat4 view = c.view(), projection = c.projectionMatrix(1.0f);
  const glm::mat4 inverseProjection = glm::inverse(projection);
  const glm::mat4 inverse = glm::inverse(projection * view);
  const auto distance = [&](float windowDepth) { return viewDistance(inverseProjection, windowDepth); };
  const auto ramp = [](float a, float b, float x) {
    return a < b ? std::clamp((x - a) / (b - a), 0.0f, 1.0f) : x > a ? 1.0f : 0.0f;
  };
  // The ray's span through an axis-aligned box of half-size h about the origin.
  const auto span = [](glm::vec3 o, glm::vec3 d, float h) {
    const glm::vec3 a = (glm::vec3(-h) - o) / d, b = (glm::vec3(h) - o) / d;
    const glm::vec3 lo = glm::min(a, b), hi = glm::max(a, b);
    return glm::vec2(std::max({lo.x, lo.y, lo.z, 0.0f}), std::min({hi.x, hi.y, hi.z}));
  };
  const float alpha = 1.0f - std::pow(1.0f - 0.3f, 0.5f);
  int compared = 0, reduced = 0;
  double worst = 0.0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const glm::vec2 uv((x + 0.5f) / s.width, 1.0f - (y + 0.5f) / s.height);
      const auto [o, d] = pixelRay(inverse, uv);
      const glm::vec2 box = span(o, d, 1.0f + 0.5f * voxel);
      const glm::vec2 probe = span(o, d, 0.25f + 0.02f);
      if (!(box.x < box.y) || probe.x < probe.y + 0.04f) continue;  // no volume, or at the cube
      // A sample that falls on the box's far side within rounding may be taken or not.
      const float last = (box.y - box.x) / step - 0.5f;
      if (std::abs(last - std::round(last)) < 0.01f) continue;
      const float z1 = distance(c1.at(x, y)[0]);
      const float z2 = std::max(distance(c2.at(x, y)[0]), z1);
      float sum = 0.0f;
      bool anyReduced = false;
      for (float t = box.x + 0.5f * step; t < box.y && sum <= 0.995f; t += step) {
        const float z = -(view * glm::vec4(o + t * d, 1.0f)).z;
        const float omega = 0.5f * ramp(-z2, -z1, -z) + 0.5f * ramp(-z1, -z1 + overlay, -z);
        const float r = ramp(std::max(2.0f * importance - 1.0f, 0.0f), importance, omega);
        anyReduced = anyReduced || r > 0.0f;
        sum += (1.0f - sum) * alpha * (1.0f - r);
      }
      const double error = std::abs(opacity.at(x, y)[0] - sum);
      worst = std::max(worst, error);
      EXPECT_NEAR(opacity.at(x, y)[0], sum, 1e-3f) << x << "," << y;
      ++compared;
      reduced += anyReduced && sum < 0.99f;
    }
  std::printf("worst opacity difference %.4f over %d pixels\n", worst, compared);
  EXPECT_GT(compared, 5000);
  EXPECT_GT(reduced, 500) << "R makes material in front of the cube translucent";
}

// Eq. 2.2 on a volume: the block's material is uniform (its gradient zero everywhere), so it
// faces the viewer wherever it is looked at, (1 − n·v)^k = 0, and edge highlights reduce each
// sample's opacity by R as translucency does (eq. 2.1). (The zero normal read as facing away
// left such material whole.)
TEST_F(VolumeTest, EdgeHighlightsReduceUniformMaterialAsTranslucencyDoes) {
  const auto translucent = renderAovs(contextualBlock(0.3f, "translucency"));
  const auto highlighted = renderAovs(contextualBlock(0.3f, "edgeHighlights"));
  const FloatImage &a = aov(translucent, "volumeOpacity"), &b = aov(highlighted, "volumeOpacity");
  int reduced = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const float expected = a.at(x, y)[0], got = b.at(x, y)[0];
      if (std::isnan(expected)) continue;
      ASSERT_NEAR(got, expected, 1e-5f) << x << "," << y;
      reduced += expected < 0.9f;
    }
  EXPECT_GT(reduced, 500);
}

// Diepstraten03 §5 on an exterior volume: the breakaway removes the samples in front of the
// interior objects' convex hull. Two small cubes at opposite corners of a block (offset 0: the
// hull is exactly the convex hull, the sweep of a cube along the segment between their
// centres). The hull's front along each ray is found here by sweeping the cube in 2000 steps;
// rays that meet the hull between the cubes enter the volume at the hull's front (within a
// step), rays that miss it enter as if uncut.
TEST_F(VolumeTest, TheBreakawayRemovesTheSamplesInFrontOfTheInteriorsHull) {
  const fs::path file = volume("block", 24, 1.0f, [](glm::vec3) { return 0.6f; });
  const std::string cube = kData + "/meshes/cube.obj";
  Scene s = scene(R"({"name": "block", "file": ")" + file.string() +
                      R"(", "shading": false, "jitter": false, "role": "exterior", )" + kRamp + "}",
                  R"(, "objects": [
          {"name": "a", "file": ")" +
                      cube + R"(", "role": "interior",
           "transform": {"translate": [-0.5, -0.5, -0.5], "scale": 0.2}},
          {"name": "b", "file": ")" +
                      cube + R"(", "role": "interior",
           "transform": {"translate": [0.3, 0.3, 0.3], "scale": 0.2}}],
        "cutters": {"breakaway": {"offset": 0}})");
  s.width = 160, s.height = 120;
  const auto aovs = renderAovs(s);
  const FloatImage& entry = aov(aovs, "volumeEntryDepth");
  const Camera c = s.resolvedCamera();
  const float aspect = float(s.width) / float(s.height);
  const glm::mat4 view = c.view(), projection = c.projectionMatrix(aspect);
  const glm::mat4 inverse = glm::inverse(projection * view);
  const glm::vec3 a(-0.4f), span(0.8f);
  // The nearest t at which the ray meets the cube of half-size h centred at a + s·span for
  // some s in [s0, s1]; infinity where it meets none.
  const auto sweep = [&](glm::vec3 o, glm::vec3 d, float h, float s0, float s1) {
    float nearest = INFINITY;
    for (int k = 0; k <= 2000; ++k) {
      const glm::vec3 centre = a + glm::mix(s0, s1, k / 2000.0f) * span;
      float lo = -INFINITY, hi = INFINITY;
      for (int i = 0; i < 3; ++i) {
        const float t0 = (centre[i] - h - o[i]) / d[i], t1 = (centre[i] + h - o[i]) / d[i];
        lo = std::max(lo, std::min(t0, t1)), hi = std::min(hi, std::max(t0, t1));
      }
      if (lo <= hi) nearest = std::min(nearest, lo);
    }
    return nearest;
  };
  const float step = 0.5f * 2.0f / 23.0f;
  int opened = 0, missed = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const glm::vec2 uv((x + 0.5f) / s.width, 1.0f - (y + 0.5f) / s.height);
      const auto [o, d] = pixelRay(inverse, uv);
      const float e = entry.at(x, y)[0];
      // Away from the hull's and the cubes' outlines by 0.02 world units.
      const bool inHull = std::isfinite(sweep(o, d, 0.08f, 0.0f, 1.0f));
      if (inHull != std::isfinite(sweep(o, d, 0.12f, 0.0f, 1.0f))) continue;
      if (!inHull) {
        const VolumeRay whole = castVolumeRay(s.volumes[0], view, projection, {s.width, s.height},
                                              {x, s.height - 1 - y});
        EXPECT_EQ(std::isnan(e), std::isnan(whole.entryDepth)) << x << "," << y;
        if (std::isnan(e)) continue;
        EXPECT_NEAR(e, whole.entryDepth, 1e-3f) << x << "," << y;
        ++missed;
        continue;
      }
      if (std::isfinite(sweep(o, d, 0.12f, 0.0f, 0.0f)) ||
          std::isfinite(sweep(o, d, 0.12f, 1.0f, 1.0f)))
        continue;  // the cubes stop the ray
      const float front = -(view * glm::vec4(o + sweep(o, d, 0.1f, 0.0f, 1.0f) * d, 1.0f)).z;
      ASSERT_FALSE(std::isnan(e)) << x << "," << y;
      EXPECT_GE(e, front - 1e-3f) << x << "," << y;
      EXPECT_LE(e, front + step + 1e-3f) << x << "," << y;
      ++opened;
    }
  EXPECT_GT(opened, 200);
  EXPECT_GT(missed, 5000);
}

// A label volume: sampled at the nearest voxel, each listed label its own material, the rest
// clear; the GPU as the CPU reference.
TEST_F(VolumeTest, ALabelVolumeShowsItsListedLabelsAsTheCpuReference) {
  const fs::path file = volume("labels", 20, 1.0f, [](glm::vec3 p) {
    return glm::length(p) < 0.5f ? 7.0f : p.x > 0.3f ? 3.0f : p.y > 0.2f ? 5.0f : 0.0f;
  });
  const Scene s = scene(R"({"name": "atlas", "file": ")" + file.string() +
                        R"(", "labels": true, "shading": false, "transferFunction": [
                          {"value": 3, "color": [0.2, 0.4, 1.0], "opacity": 0.2},
                          {"value": 7, "color": [1.0, 0.8, 0.2], "opacity": 0.9}]})");
  Renderer renderer(s, test::glContext().info());
  renderer.render();
  const auto aovs = renderer.readAovs();
  const FloatImage& opacity = aov(aovs, "volumeOpacity");
  const Camera c = s.resolvedCamera();
  const float aspect = float(s.width) / float(s.height);
  int seen = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const VolumeRay cpu = castVolumeRay(s.volumes[0], c.view(), c.projectionMatrix(aspect),
                                          {s.width, s.height}, {x, s.height - 1 - y});
      // Exact but where a sample lies within rounding of a voxel boundary.
      if (std::abs(opacity.at(x, y)[0] - cpu.opacity) > 0.02f) ++seen;
    }
  EXPECT_LT(seen, s.width * s.height / 50) << "pixels unlike the CPU reference";
  // Label 5 is not listed: a ray through it alone (above the sphere, left of x = 0.3) is clear.
  EXPECT_EQ(s.volumes[0].material(5.0f).opacity, 0.0f);
  EXPECT_EQ(s.volumes[0].material(7.2f).opacity, 0.9f);
}

// A volume of interest seeds the cutaway with the rear of its material: the seed depth is
// the far side of a labelled sphere, within a voxel and a step.
TEST_F(VolumeTest, AVolumeOfInterestSeedsTheCutawayWithItsRear) {
  const float radius = 0.4f;
  const fs::path sphere = volume(
      "sphere", 32, 1.0f, [&](glm::vec3 p) { return glm::length(p) < radius ? 1.0f : 0.0f; });
  const fs::path fog = volume("fog", 12, 1.0f, [](glm::vec3) { return 1.0f; });
  const Scene s = scene(R"({"name": "fog", "file": ")" + fog.string() + R"(", "shading": false,
                          "transferFunction": [{"value": 0, "opacity": 0}, {"value": 1, "opacity": 0.05}]},
                        {"name": "target", "file": ")" +
                            sphere.string() + R"(", "role": "interest",
                          "labels": true, "transferFunction": [{"value": 1, "opacity": 1}]})",
                        R"(, "cutters": {"adaptive": {"angle": 30}})");
  const auto aovs = renderAovs(s);
  const FloatImage& seed = aov(aovs, "seedDepth");
  const Camera c = s.resolvedCamera();
  const float aspect = float(s.width) / float(s.height);
  const glm::mat4 inverse = glm::inverse(c.projectionMatrix(aspect) * c.view());
  const float voxel = 2.0f / 31.0f;
  int seeded = 0;
  for (int y = 0; y < seed.height; ++y)
    for (int x = 0; x < seed.width; ++x) {
      const glm::vec2 uv((x + 0.5f) / seed.width, 1.0f - (y + 0.5f) / seed.height);
      const auto [o, d] = pixelRay(inverse, uv);
      // Rays clearly through the sphere: the rear at the far intersection.
      const float near = sphereHit(o, d, radius - voxel);
      const float w = seed.at(x, y)[0];
      if (sphereHit(o, d, radius + voxel) < 0.0f) {
        EXPECT_EQ(w, 0.0f) << "a seed off the sphere at " << x << "," << y;
        continue;
      }
      if (near < 0.0f) continue;
      ++seeded;
      const float bq = glm::dot(o, d);
      const float far = -bq + std::sqrt(bq * bq - glm::dot(o, o) + radius * radius);
      // The seed's point along the ray: the labelled voxels' boundary lies within half a
      // voxel's diagonal (√3/2) of the sphere, the back-to-front march finds it within a step
      // (half a voxel): two voxels.
      const glm::vec4 q = inverse * glm::vec4(uv * 2.0f - 1.0f, w * 2.0f - 1.0f, 1.0f);
      EXPECT_NEAR(glm::distance(glm::vec3(q) / q.w, o), far, 2.0f * voxel) << x << "," << y;
    }
  EXPECT_GT(seeded, 100);
}

// Line drawings (Burns11 §2.4, kinds/volumes/volume_lines_pass.hpp): a ball A in front of a
// ball B that it hides entirely, as signed distances. Every drawn contour point's view ray
// grazes the ball it belongs to (its distance from the centre is the radius); B's contour is
// hidden behind A, drawn faint when dimmed, and seen again when a box cut removes A.
struct Ball {
  glm::vec3 centre;
  float radius;
};
constexpr Ball kFront{{0.0f, 0.0f, 0.5f}, 0.45f}, kBack{{0.0f, 0.0f, -0.45f}, 0.5f};

struct GrazedLines {
  int front = 0, back = 0, other = 0;  // drawn points grazing A, grazing B, neither
  int hidden = 0;                      // of them, in hidden lines
};

GrazedLines graze(const Scene& s, const VolumeLineDrawing& d) {
  const Camera c = s.resolvedCamera();
  const glm::mat4 inverse =
      glm::inverse(c.projectionMatrix(float(s.width) / float(s.height)) * c.view());
  const float pixel = 2.0f * 4.0f * std::tan(glm::radians(20.0f)) / float(s.height);
  GrazedLines g;
  for (const DrawnVolumeLine& line : d.lines)
    for (const glm::vec2& p : line.points) {
      const PixelRay r = pixelRay(inverse, {p.x / float(d.width), 1.0f - p.y / float(d.height)});
      const auto off = [&](const Ball& b) {
        return std::abs(glm::length(glm::cross(b.centre - r.o, r.d)) - b.radius);
      };
      const float tolerance = 1.5f * pixel;
      (off(kFront) < tolerance ? g.front : off(kBack) < tolerance ? g.back : g.other) += 1;
      g.hidden += line.hidden;
    }
  return g;
}

// A noise volume's lines past the style's "mostSegments": the frame fails with an error that
// names the scene, the volume's lines and the budget; within it, the frame is drawn.
TEST_F(VolumeTest, LinesOfNoisePastTheirBudgetFailTheFrameWithAClearError) {
  const fs::path file = volume("noise", 32, 1.0f, [](glm::vec3 p) {
    const glm::uvec3 q(glm::ivec3(glm::round(p * 100.0f)) + 1000);
    std::uint32_t h = q.x * 73856093u ^ q.y * 19349663u ^ q.z * 83492791u;
    h ^= h >> 13, h *= 0x5bd1e995u, h ^= h >> 15;
    return float(h & 0xffffu) / 65535.0f - 0.5f;
  });
  const auto withBudget = [&](int most) {
    return scene(R"({"name": "noise", "file": ")" + file.string() + R"(", )" + kRamp +
                 R"(, "lines": {"isoValues": [{"value": -0.2}, {"value": 0}, {"value": 0.2}], )"
                 R"("mostSegments": )" +
                 std::to_string(most) + "}}");
  };
  const Scene tight = withBudget(5000), roomy = withBudget(4'000'000);  // renderers refer to them
  Renderer bounded(tight, test::glContext().info());
  try {
    bounded.render();
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind(
                  "volumes.json: /volumes/0/lines: the lines hold more than 5000 segments "
                  "(\"mostSegments\"), reached at isovalue ",
                  0),
              0u)
        << e.what();
  }
  Renderer drawn(roomy, test::glContext().info());
  drawn.render();
  EXPECT_GT(drawn.volumeLineDrawing().lines.size(), 100u);
}

TEST_F(VolumeTest, LinesAreDrawnWhereTheyGrazeTheSurfaceAndHiddenBehindNearerOnes) {
  const fs::path file = volume("balls", 48, 1.0f, [](glm::vec3 p) {
    return std::max(kFront.radius - glm::distance(p, kFront.centre),
                    kBack.radius - glm::distance(p, kBack.centre));
  });
  const auto lines = [&](const std::string& style, const std::string& rest = "") {
    Scene s = scene(R"({"name": "balls", "file": ")" + file.string() + R"(", )" + kRamp +
                        R"(, "lines": {"isoValues": [{"value": 0}], "only": true, "halo": 0, )" +
                        style + "}}",
                    rest);
    s.camera.eye = {0.0f, 0.0f, 4.0f};
    s.width = s.height = 160;
    Renderer renderer(s, test::glContext().info());
    renderer.render();
    const VolumeLineDrawing d = renderer.volumeLineDrawing();
    // The coverage AOV holds the drawn lines: every covered pixel lies within a line's
    // half width (and its antialiasing) of a drawn segment.
    const FloatImage coverage = aov(renderer.readAovs(), "volumeLineCoverage");
    int covered = 0, stray = 0;
    for (int y = 0; y < coverage.height; ++y)
      for (int x = 0; x < coverage.width; ++x) {
        if (!(coverage.at(x, y)[0] > 0.5f)) continue;
        ++covered;
        const glm::vec2 c(float(x) + 0.5f, float(y) + 0.5f);
        float nearest = 1e9f;
        for (const DrawnVolumeLine& l : d.lines)
          for (std::size_t i = 0; i + 1 < l.points.size(); ++i) {
            const glm::vec2 a = l.points[i], ab = l.points[i + 1] - a;
            const float t =
                glm::clamp(glm::dot(c - a, ab) / std::max(glm::dot(ab, ab), 1e-9f), 0.0f, 1.0f);
            nearest = std::min(nearest, glm::distance(c, a + t * ab));
          }
        stray += nearest > 2.5f;
      }
    EXPECT_EQ(stray, 0) << "of " << covered << " covered pixels, away from every drawn segment";
    return std::pair{graze(s, d), covered};
  };
  {
    const auto [g, covered] = lines(R"("hidden": "removed")");
    EXPECT_GT(g.front, 50);
    EXPECT_EQ(g.back, 0) << "B's contour lies behind A";
    EXPECT_LT(g.other, g.front / 50);
    EXPECT_GT(covered, 150);
  }
  {
    const auto [g, covered] = lines(R"("hidden": "dimmed")");
    EXPECT_GT(g.front, 50);
    EXPECT_GT(g.back, 50) << "B's contour drawn faint";
    EXPECT_GE(g.hidden, g.back);
  }
  {
    // Cut away A: B's contour shows through the cut, A's is gone where the box removes it.
    const auto [g, covered] =
        lines(R"("hidden": "removed")",
              R"(, "cutters": {"boxCut": {"center": [0, 0, 0.5], "size": [1.2, 1.2, 1.0]}})");
    EXPECT_EQ(g.front, 0);
    EXPECT_GT(g.back, 50);
    EXPECT_EQ(g.hidden, 0);
  }
}

// Halos (Appel et al. 1979, Burns11 §2.4.2): two balls' contours cross on screen, A's 0.8
// units (19 voxels) in front of B's. With halos of 8 pixels and hidden lines shown, B's
// contour is broken within A's half width + 8 pixels of A's contour, on each side, and drawn
// beyond; A's contour is whole. Checked on the drawn polylines (points every half pixel)
// against the coverage AOV over each point's 3 × 3 pixels; points within 1.5 pixels of the
// halo's edge or of A's line may go either way.
TEST_F(VolumeTest, AHaloBreaksALineFarBehindANearerOneAndNothingElse) {
  const Ball a{{-0.2f, 0.0f, 0.4f}, 0.35f}, b{{0.2f, 0.0f, -0.4f}, 0.35f};
  const fs::path file = volume("balls", 48, 1.0f, [&](glm::vec3 p) {
    return std::max(a.radius - glm::distance(p, a.centre), b.radius - glm::distance(p, b.centre));
  });
  const Scene s = parseScene(
      R"({"resolution": [160, 160], "samples": 1, "background": [1, 1, 1],
          "style": {"name": "gooch", "lines": false},
          "camera": {"projection": "orthographic", "height": 2, "eye": [0, 0, 4],
                     "target": [0, 0, 0]},
          "volumes": [{"name": "balls", "file": ")" +
          file.string() + R"(", )" + kRamp +
          R"(, "lines": {"isoValues": [{"value": 0, "width": 1}], "only": true,
                         "hidden": "shown", "halo": 8}}]})",
      "halos.json", dir_);
  Renderer renderer(s, test::glContext().info());
  renderer.render();
  const VolumeLineDrawing d = renderer.volumeLineDrawing();
  const FloatImage coverage = aov(renderer.readAovs(), "volumeLineCoverage");
  const float pixelsPerUnit = 80.0f;
  const auto onScreen = [&](const Ball& ball) {
    return glm::vec2((ball.centre.x + 1.0f) * pixelsPerUnit,
                     (1.0f - ball.centre.y) * pixelsPerUnit);
  };
  const auto isA = [&](const DrawnVolumeLine& l) {
    return std::abs(glm::distance(l.points.front(), onScreen(a)) - a.radius * pixelsPerUnit) <
           std::abs(glm::distance(l.points.front(), onScreen(b)) - b.radius * pixelsPerUnit);
  };
  const auto around = [&](glm::vec2 q) {  // the most coverage over the 3 × 3 pixels at q
    float most = 0.0f;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int x = int(q.x) + dx, y = int(q.y) + dy;
        if (x >= 0 && y >= 0 && x < coverage.width && y < coverage.height)
          most = std::max(most, coverage.at(x, y)[0]);
      }
    return most;
  };
  // Points every half pixel along the lines of A (or of B).
  const auto points = [&](bool ofA) {
    std::vector<glm::vec2> out;
    for (const DrawnVolumeLine& l : d.lines) {
      if (isA(l) != ofA) continue;
      for (std::size_t i = 0; i + 1 < l.points.size(); ++i) {
        const int n =
            std::max(1, int(std::ceil(2.0f * glm::distance(l.points[i], l.points[i + 1]))));
        for (int k = 0; k < n; ++k)
          out.push_back(glm::mix(l.points[i], l.points[i + 1], float(k) / float(n)));
      }
    }
    return out;
  };
  const std::vector<glm::vec2> onA = points(true), onB = points(false);
  ASSERT_GT(onA.size(), 200u);
  ASSERT_GT(onB.size(), 200u);
  int broken = 0, drawn = 0, aMissing = 0;
  test::Mismatches wrong;  // line coverage around a point of B: 0 where broken, 1 where drawn
  for (const glm::vec2& q : onB) {
    float toA = 1e9f;
    for (const glm::vec2& p : onA) toA = std::min(toA, glm::distance(p, q));
    const float edge = 0.5f + 8.0f;  // A's half width and the halo
    if (toA > 3.0f && toA < edge - 1.5f) {
      ++broken;
      if (around(q) > 0.1f) wrong.add(int(q.x), int(q.y), 0.0, around(q));
    } else if (toA > edge + 1.5f) {
      ++drawn;
      if (around(q) < 0.5f) wrong.add(int(q.x), int(q.y), 1.0, around(q));
    }
  }
  for (const glm::vec2& q : onA) aMissing += around(q) < 0.5f;
  EXPECT_GT(broken, 10);
  EXPECT_GT(drawn, 200);
  EXPECT_EQ(wrong.count(), 0) << "of " << broken + drawn << ": " << wrong;
  EXPECT_EQ(aMissing, 0) << "of " << onA.size();
}

// The SVG holds the drawing: its polylines, read back, are the drawn runs point for point.
TEST_F(VolumeTest, TheLinesSvgHoldsTheDrawnPolylines) {
  const fs::path file = volume("ball", 32, 1.0f, [](glm::vec3 p) { return 0.6f - glm::length(p); });
  Scene s =
      scene(R"({"name": "ball", "file": ")" + file.string() + R"(", )" + kRamp +
            R"(, "lines": {"isoValues": [{"value": 0, "color": [0.8, 0.1, 0.1], "width": 2.5}],
                                 "planes": [{"normal": [0, 1, 0], "distance": 0.2}], "halo": 1.5}})");
  Renderer renderer(s, test::glContext().info());
  renderer.render();
  const VolumeLineDrawing d = renderer.volumeLineDrawing();
  ASSERT_FALSE(d.lines.empty());
  const std::string svg = volumeLineSvg(d);
  // Each line's polyline (after its halo's), in the drawing's far-to-near order.
  std::vector<const DrawnVolumeLine*> order;
  for (const auto& l : d.lines) order.push_back(&l);
  std::stable_sort(order.begin(), order.end(),
                   [](auto* a, auto* b) { return a->depth > b->depth; });
  const std::regex polyline(
      R"(<polyline class='(halo|line)[^']*' fill='none' stroke='(#[0-9a-f]{6})' stroke-width='([0-9.]+)'[^>]*points='([^']*)'/>)");
  std::size_t next = 0, halos = 0;
  std::set<std::string> colours;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), polyline);
       it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    if (m[1] == "halo") {
      ++halos;
      continue;
    }
    ASSERT_LT(next, order.size());
    const DrawnVolumeLine& l = *order[next++];
    colours.insert(m[2]);
    EXPECT_FLOAT_EQ(std::stof(m[3]), l.width);
    std::istringstream points(m[4]);
    std::size_t i = 0;
    for (std::string xy; points >> xy; ++i) {
      ASSERT_LT(i, l.points.size());
      const auto comma = xy.find(',');
      EXPECT_NEAR(std::stof(xy.substr(0, comma)), l.points[i].x, 0.006f);
      EXPECT_NEAR(std::stof(xy.substr(comma + 1)), l.points[i].y, 0.006f);
    }
    EXPECT_EQ(i, l.points.size());
  }
  EXPECT_EQ(next, d.lines.size());
  EXPECT_EQ(halos, d.lines.size());  // none hidden here
  EXPECT_TRUE(colours.count("#cc1a1a")) << "the contour's pen";
  EXPECT_TRUE(colours.count("#1a4db3")) << "the plane cut's pen";
}

TEST_F(VolumeTest, BadVolumeEntriesAreRejectedWithTheirPlace) {
  const fs::path file = volume("v", 4, 1.0f, [](glm::vec3) { return 0.0f; });
  const std::string f = R"("name": "v", "file": ")" + file.string() + "\", ";
  expectError(
      [&] {
        scene("{" + f +
              R"("mode": "isosurface", "transferFunction": [{"value": 0, "opacity": 1}]})");
      },
      {"/volumes/0", "isoValue"});
  expectError(
      [&] {
        scene("{" + f +
              R"("transferFunction": [{"value": 1, "opacity": 1}, {"value": 0, "opacity": 0}]})");
      },
      {"/volumes/0/transferFunction/1/value", "increasing"});
  expectError([&] { scene("{" + f + R"("transferFunction": []})"); },
              {"/volumes/0/transferFunction"});
  expectError(
      [&] {
        scene("{" + f + R"("mode": "xray", "transferFunction": [{"value": 0, "opacity": 1}]})");
      },
      {"/volumes/0/mode", "xray"});
  expectError(
      [&] {
        scene("{" + f +
              R"("sampleDistance": 0, "transferFunction": [{"value": 0, "opacity": 1}]})");
      },
      {"/volumes/0/sampleDistance"});
  expectError(
      [&] {
        scene(
            R"({"name": "v", "file": "missing.nii.gz", "transferFunction": [{"value": 0, "opacity": 1}]})");
      },
      {"/volumes/0/file", "missing.nii.gz"});
  expectError(
      [&] { scene("{" + f + R"("transferFunction": [{"value": 0, "opacity": 1}], "colour": 1})"); },
      {"/volumes/0", "colour"});
  // Lines: isovalues required (one to eight), known keys, a plane's normal not zero, no labels.
  const std::string tf = R"("transferFunction": [{"value": 0, "opacity": 1}], )";
  // (lines, the place, a word of the reason)
  const std::vector<std::array<std::string, 3>> badLines{
      {R"({"contours": true})", "/volumes/0/lines", "isoValues"},
      {R"({"isoValues": []})", "/volumes/0/lines/isoValues", ""},
      {R"({"isoValues": [{"color": [0, 0, 0]}]})", "/volumes/0/lines/isoValues/0", "value"},
      {R"({"isoValues": [{"value": 0}], "halos": 2})", "/volumes/0/lines", "halos"},
      {R"({"isoValues": [{"value": 0}], "hidden": "faint"})", "/volumes/0/lines/hidden", "faint"},
      {R"({"isoValues": [{"value": 0}], "planes": [{"normal": [0, 0, 0]}]})",
       "/volumes/0/lines/planes/0/normal", ""},
      {R"({"isoValues": [{"value": 0, "width": 100}]})", "/volumes/0/lines/isoValues/0/width", ""}};
  for (const auto& [lines, place, reason] : badLines) {
    SCOPED_TRACE(lines);
    expectError([&, &json = lines] { scene("{" + f + tf + R"("lines": )" + json + "}"); },
                {place, reason});
  }
  expectError(
      [&] { scene("{" + f + tf + R"("labels": true, "lines": {"isoValues": [{"value": 0}]}})"); },
      {"/volumes/0/lines", "label volume"});
  const std::string row = R"({"gradient": 0, "points": [{"value": 0, "opacity": 1}]})";
  expectError(
      [&] {
        scene("{" + f + R"("transferFunction": [{"value": 0, "opacity": 1}], "transferFunction2D": [)" +
              row + "]}");
      },
      {"/volumes/0/transferFunction2D", "not both"});
  expectError([&] { scene("{" + f + R"("transferFunction2D": [)" + row + ", " + row + "]}"); },
              {"/volumes/0/transferFunction2D/1/gradient", "increasing"});
  expectError([&] { scene("{" + f + R"("transferFunction2D": [{"gradient": 0}]})"); },
              {"/volumes/0/transferFunction2D/0", "points"});
  expectError(
      [&] { scene("{" + f + R"("labels": true, "transferFunction2D": [)" + row + "]}"); },
      {"/volumes/0/transferFunction2D", "per label"});
}
