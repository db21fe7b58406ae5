// Tests of the toon, hatching and shadow styles: the tonal art map's nesting and tones on the
// CPU (Praun01 §3.2), the toon ramp's bands in a rendered frame against the ramp evaluated at
// the analytic n·l (Lake00 §3.1), and shadows against a CPU ray–box test.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <optional>
#include <set>

#include "cutaway/render/renderer.hpp"
#include "cutaway/styles/hatching.hpp"
#include "cutaway/styles/toon.hpp"
#include "gl_test_context.hpp"
#include "render_aovs.hpp"
#include "styles/hatching/tonal_art_map.hpp"
#include "styles/shadows/shadow_map.hpp"
#include "styles/toon/toon_ramp.hpp"

using namespace cutaway;

namespace {

const std::string kData = CUTAWAY_TEST_DATA;

const Aov& findAov(const std::vector<Aov>& aovs, const std::string& name) {
  for (const auto& a : aovs)
    if (a.name == name) return a;
  throw std::runtime_error("no AOV " + name);
}

const TonalArtMap& defaultTam() {
  static const TonalArtMap tam = generateTonalArtMap({});
  return tam;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Tonal art map (CPU).

// Praun01 §3.2: every stroke of a tone is in all darker tones, so each texel of tone k + 1 is
// at least as dark as in tone k; a stroke texel of tone k (ink ≥ 0.5) stays a stroke texel.
TEST(TonalArtMap, EveryStrokeOfAToneIsInTheNextDarkerTone) {
  const TonalArtMap& tam = defaultTam();
  ASSERT_EQ(tam.tones, 6);
  for (int level = 0; level < tam.levels; ++level)
    for (int tone = 0; tone + 1 < tam.tones; ++tone) {
      const auto& lighter = tam.ink(level, tone);
      const auto& darker = tam.ink(level, tone + 1);
      int strokeTexels = 0;
      for (std::size_t i = 0; i < lighter.size(); ++i) {
        // 1e-6: ink composes in float, in a different order in the two tones.
        ASSERT_GE(darker[i], lighter[i] - 1e-6f)
            << "level " << level << " tone " << tone << " texel " << i;
        if (lighter[i] >= 0.5f) {
          ++strokeTexels;
          ASSERT_GE(darker[i], 0.5f) << "level " << level << " tone " << tone << " texel " << i;
        }
      }
      EXPECT_GT(strokeTexels, 0) << "level " << level << " tone " << tone << " has no strokes";
    }
}

// Mean ink rises with the tone at every level and meets the tone's target: strokes are added
// until the mean passes the target, so it overshoots by at most about one stroke's ink.
TEST(TonalArtMap, MeanInkRisesAcrossTonesAndMeetsTheTargets) {
  const TonalArtMap& tam = defaultTam();
  for (int level = 0; level < tam.levels; ++level) {
    const double texels = double(tam.width(level)) * tam.width(level);
    // A stroke is at most 0.5 · width long and about 2 texels wide with its anti-aliasing.
    const double oneStroke = 0.5 * tam.width(level) * 2.0 / texels;
    double previous = 0.0;
    for (int tone = 0; tone < tam.tones; ++tone) {
      const double mean = tam.meanInk(level, tone);
      const double target = tonalArtMapTarget(tone, tam.tones);
      EXPECT_GT(mean, previous) << "level " << level << " tone " << tone;
      EXPECT_GE(mean, target) << "level " << level << " tone " << tone;
      EXPECT_LE(mean, target + oneStroke + 1e-9)
          << "level " << level << " tone " << tone << ": mean " << mean << ", target " << target;
      previous = mean;
    }
  }
  EXPECT_NEAR(tonalArtMapTarget(5, 6), kTonalArtMapDarkest, 1e-7);
}

// Every level of a tone is built to the same target, so a change of mipmap level does not
// change the tone (within about a stroke of the coarsest level); the same seed gives the same
// TAM, another seed other strokes.
TEST(TonalArtMap, LevelsAgreeInToneAndSeedsDiffer) {
  const TonalArtMap& tam = defaultTam();
  for (int tone = 0; tone < tam.tones; ++tone)
    for (int level = 1; level < tam.levels; ++level)
      EXPECT_NEAR(tam.meanInk(level, tone), tam.meanInk(0, tone), 0.1)
          << "level " << level << " tone " << tone;
  const TonalArtMap again = generateTonalArtMap({});
  EXPECT_EQ(again.ink(2, 3), tam.ink(2, 3));  // deterministic
  const TonalArtMap other = generateTonalArtMap({.seed = 7});
  EXPECT_NE(other.ink(2, 3), tam.ink(2, 3));
}

// ---------------------------------------------------------------------------------------------
// Toon ramp.

TEST(ToonRamp, DiffuseTermSplitsIntoEqualBands) {
  EXPECT_EQ(toonRampIndex(3, -0.5f), 0);
  EXPECT_EQ(toonRampIndex(3, 0.0f), 0);
  EXPECT_EQ(toonRampIndex(3, 0.33f), 0);
  EXPECT_EQ(toonRampIndex(3, 0.34f), 1);
  EXPECT_EQ(toonRampIndex(3, 0.66f), 1);
  EXPECT_EQ(toonRampIndex(3, 0.67f), 2);
  EXPECT_EQ(toonRampIndex(3, 1.0f), 2);
  EXPECT_EQ(toonRampIndex(4, 0.5f), 2);
  ToonStyle style;
  EXPECT_EQ(toonRampTexels(style).size(), 3u);
}

// A plane facing the camera, lit by a point light 1 unit in front of it: n·l = 1/√(r² + 1)
// falls from 1 at the centre to 0.2 in the corners, through all three bands. Each pixel must
// show exactly the ramp colour (8-bit texel × object colour) of the band of its analytic n·l,
// except within 0.01 of a band edge, where interpolation and rounding may fall either way.
TEST(ToonRender, PlaneShowsExactlyTheRampColours) {
  const Scene scene = parseScene(R"({
      "resolution": [80, 60], "samples": 1,
      "style": {"name": "toon", "lines": false,
                "toon": {"ramp": [[0.2, 0.3, 0.6], 0.55, [1, 0.9, 0.8]], "highlight": false}},
      "lights": [{"type": "point", "position": [0, 0, 1], "space": "world"}],
      "camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "fov": 60, "near": 1, "far": 11},
      "objects": [{"name": "plane", "file": "plane.obj", "color": [0.9, 0.8, 0.7]}]})",
                                 "toon-plane.json", kData + "/render");
  Renderer renderer(scene, test::glContext().info());
  renderer.render();
  const Rgba8Image color = renderer.readColor();
  const auto aovs = renderer.readAovs();
  const FloatImage& position = findAov(aovs, "position").image;
  const FloatImage& objectId = findAov(aovs, "objectId").image;
  const auto texels = toonRampTexels(scene.style.get<ToonStyle>());
  const int n = int(texels.size());
  std::set<int> bands;
  int checked = 0;
  for (int y = 0; y < scene.height; ++y)
    for (int x = 0; x < scene.width; ++x) {
      ASSERT_EQ(objectId.at(x, y)[0], 0.0f) << x << "," << y;
      const glm::vec3 p(position.at(x, y)[0], position.at(x, y)[1], position.at(x, y)[2]);
      const float nDotL = glm::normalize(glm::vec3(0, 0, 1) - p).z;
      const float band = nDotL * float(n);
      if (std::abs(band - std::round(band)) < 0.01f * n) continue;
      const int index = toonRampIndex(n, nDotL);
      bands.insert(index);
      ++checked;
      for (int c = 0; c < 3; ++c) {
        const float texel = std::round(texels[std::size_t(index)][c] * 255.0f) / 255.0f;
        const float expected = texel * scene.objects[0].material.color[c] * 255.0f;
        EXPECT_NEAR(float(color.at(x, y)[c]), expected, 1.0f)
            << "pixel " << x << "," << y << " channel " << c << " n·l " << nDotL << " band "
            << index;
      }
    }
  EXPECT_EQ(bands.size(), 3u);
  EXPECT_GT(checked, scene.width * scene.height * 9 / 10);
}

// ---------------------------------------------------------------------------------------------
// Shadows.

// The light's frustum holds the whole scene: every corner of the bounds maps into [0, 1]³
// (for point lights outside the bounds; from inside, no single frustum sees all around).
TEST(ShadowFrustum, BoundsFitInsideForDirectionalAndPointLights) {
  Bounds b;
  b.extend(glm::vec3(-3, -1, 2));
  b.extend(glm::vec3(5, 4, 6));
  for (const glm::vec4 light :
       {glm::vec4(0.3f, -1, 0.2f, 0), glm::vec4(0, 0, 1, 0), glm::vec4(0, 1, 0, 0),
        glm::vec4(10, 20, 30, 1), glm::vec4(6, 5, 7, 1)}) {
    const LightFrustum f = keyLightFrustum(light, b);
    EXPECT_EQ(f.orthographic, light.w == 0.0f);
    const glm::mat4 m = shadowMatrix(f);
    for (int i = 0; i < 8; ++i) {
      const glm::vec3 corner((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y,
                             (i & 4) ? b.max.z : b.min.z);
      const glm::vec4 h = m * glm::vec4(corner, 1.0f);
      const glm::vec3 p = glm::vec3(h) / h.w;
      for (int k = 0; k < 3; ++k) {
        EXPECT_GE(p[k], 0.0f) << "light " << light.x << "," << light.y << "," << light.z
                              << " corner " << i << " axis " << k;
        EXPECT_LE(p[k], 1.0f) << "light " << light.x << "," << light.y << "," << light.z
                              << " corner " << i << " axis " << k;
      }
    }
  }
}

namespace {

// Ray–box intersection (slabs) for 0 < t < tMax.
bool hitsBox(const glm::vec3& origin, const glm::vec3& direction, const glm::vec3& lo,
             const glm::vec3& hi, float tMax = 1e30f) {
  float t0 = 0.0f, t1 = tMax;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(direction[k]) < 1e-12f) {
      if (origin[k] < lo[k] || origin[k] > hi[k]) return false;
      continue;
    }
    float a = (lo[k] - origin[k]) / direction[k], b = (hi[k] - origin[k]) / direction[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a), t1 = std::min(t1, b);
  }
  return t0 <= t1;
}

struct ShadowCount {
  int shadowed = 0, lit = 0, wrongShadowed = 0, wrongLit = 0;
};

// tests/data/render/box-shadow.json: a 2-unit box floating 1.5 above the ground plane y = 0,
// lit from above (box-shadow-point.json: by a point light). For each ground pixel, the ray from its
// position (position AOV) towards the light decides on the CPU whether the box shadows it; pixels
// within `margin` of the shadow's edge (rays that hit the box grown by it but miss it shrunk by it)
// are left out: PCF softens the edge over a few shadow-map texels. Shadowed ground in Blinn-Phong
// is the ambient 0.15 × 0.8 = 0.12, lit ground 0.12 + 0.8 n·l (plus a highlight); a pixel counts as
// rendered in shadow when its red is below the midpoint of the two.
ShadowCount countShadows(const Scene& scene) {
  Renderer renderer(scene, test::glContext().info());
  renderer.render();
  const Rgba8Image color = renderer.readColor();
  const auto aovs = renderer.readAovs();
  const FloatImage& position = findAov(aovs, "position").image;
  const FloatImage& objectId = findAov(aovs, "objectId").image;
  const Light& light = scene.lights[0];
  const glm::vec3 lo(-1, 1.5f, -1), hi(1, 3.5f, 1);
  const float margin = 0.1f;
  ShadowCount count;
  for (int y = 0; y < scene.height; ++y)
    for (int x = 0; x < scene.width; ++x) {
      if (objectId.at(x, y)[0] != 0.0f) continue;  // ground only
      const glm::vec3 p(position.at(x, y)[0], position.at(x, y)[1], position.at(x, y)[2]);
      const bool point = light.type == Light::Type::Point;
      const glm::vec3 toLight = point ? light.position - p : -light.direction;
      const float tMax = point ? 1.0f : 1e30f;  // up to the light, not beyond
      const bool inner = hitsBox(p, toLight, lo + margin, hi - margin, tMax);
      const bool outer = hitsBox(p, toLight, lo - margin, hi + margin, tMax);
      if (inner != outer) continue;
      const float red = color.at(x, y)[0];
      // Ground normal +y; in double, for lights whose squared distance overflows a float.
      const float nDotL = std::max(float(glm::normalize(glm::dvec3(toLight)).y), 0.0f);
      const float shadowRed = 0.12f * 255.0f, litRed = (0.12f + 0.8f * nDotL) * 255.0f;
      const bool renderedDark = red < 0.5f * (shadowRed + litRed);
      if (inner) {
        ++count.shadowed;
        if (!renderedDark) ++count.wrongLit;
      } else {
        ++count.lit;
        if (renderedDark) ++count.wrongShadowed;
      }
    }
  return count;
}

Scene boxShadowScene() {
  return loadScene(kData + "/render/box-shadow.json");
}

}  // namespace

TEST(ShadowRender, GroundIsDarkExactlyWhereTheBoxBlocksTheLight) {
  const ShadowCount c = countShadows(boxShadowScene());
  EXPECT_GT(c.shadowed, 100);
  EXPECT_GT(c.lit, 2000);
  EXPECT_EQ(c.wrongLit, 0) << "shadowed pixels rendered lit";
  EXPECT_EQ(c.wrongShadowed, 0) << "lit pixels rendered shadowed (acne or a shifted shadow)";
}

// A point light: a perspective shadow map from its position (the box's shadow is larger than
// the box, and falls away from the light).
TEST(ShadowRender, PointLightShadowMatchesTheRayBoxTest) {
  const ShadowCount c = countShadows(loadScene(kData + "/render/box-shadow-point.json"));
  EXPECT_GT(c.shadowed, 100);
  EXPECT_GT(c.lit, 2000);
  EXPECT_EQ(c.wrongLit, 0) << "shadowed pixels rendered lit";
  EXPECT_EQ(c.wrongShadowed, 0) << "lit pixels rendered shadowed (acne or a shifted shadow)";
}

// A point light far beyond the scene casts as the directional light along its axis does: at
// 3e7 units its perspective map held the scene within one float step of that distance, and
// the ground rendered all dark; from 1e19 on, the float square of its distance overflowed and
// the whole frame was black. Positions reach 1e30.
TEST(ShadowRender, AFarPointLightShadowMatchesTheRayBoxTest) {
  Scene scene = boxShadowScene();
  Light& light = scene.lights[0];
  light.type = Light::Type::Point;
  for (const float distance : {3e7f, 1e20f, 1e30f}) {
    SCOPED_TRACE(distance);
    light.position = -distance * glm::normalize(light.direction);
    const ShadowCount c = countShadows(scene);
    EXPECT_GT(c.shadowed, 100);
    EXPECT_GT(c.lit, 2000);
    EXPECT_EQ(c.wrongLit, 0) << "shadowed pixels rendered lit";
    EXPECT_EQ(c.wrongShadowed, 0) << "lit pixels rendered shadowed";
  }
  light.position = -3e7f * glm::normalize(light.direction);
  const LightFrustum far = keyLightFrustum(glm::vec4(light.position, 1.0f), scene.bounds());
  EXPECT_TRUE(far.orthographic);
  const LightFrustum near =
      keyLightFrustum(glm::vec4(light.position * 1e-4f, 1.0f), scene.bounds());
  EXPECT_FALSE(near.orthographic);
}

TEST(ShadowRender, CastersFollowRoleAndCastsShadow) {
  {
    Scene scene = boxShadowScene();
    scene.objects[1].role = Role::Exterior;  // exterior shells do not cast by default
    const ShadowCount c = countShadows(scene);
    EXPECT_EQ(c.shadowed - c.wrongLit, 0);
  }
  {
    Scene scene = boxShadowScene();
    scene.objects[1].role = Role::Exterior;
    scene.objects[1].params["castsShadow"] = true;
    const ShadowCount c = countShadows(scene);
    EXPECT_EQ(c.wrongLit, 0);
    EXPECT_EQ(c.wrongShadowed, 0);
  }
  {
    Scene scene = boxShadowScene();
    scene.objects[1].params["castsShadow"] = false;
    const ShadowCount c = countShadows(scene);
    EXPECT_EQ(c.shadowed - c.wrongLit, 0);
  }
}

// The shadow map is an AOV: depth along the light's axis in scene units, 0 where nothing
// casts. Checked at the texels where the box's top centre and a bare ground point project,
// against their depths in the light's view computed on the CPU.
TEST(ShadowRender, ShadowMapIsAnAovWithAMeaning) {
  const Scene scene = boxShadowScene();
  Renderer renderer(scene, test::glContext().info());
  renderer.render();
  const auto aovs = renderer.readAovs();
  const Aov& map = findAov(aovs, "shadowMap");
  EXPECT_NE(map.meaning.find("key light"), std::string::npos) << map.meaning;
  const int size = scene.style.shadows.size;
  ASSERT_EQ(map.image.width, size);
  const LightFrustum light =
      keyLightFrustum(glm::vec4(glm::normalize(scene.lights[0].direction), 0.0f), scene.bounds());
  const glm::mat4 toMap = shadowMatrix(light);
  for (const glm::vec3 q : {glm::vec3(0, 3.5f, 0), glm::vec3(6, 0, 5), glm::vec3(-7, 0, -2)}) {
    const glm::vec4 h = toMap * glm::vec4(q, 1.0f);
    const int x = int(h.x / h.w * size), y = size - 1 - int(h.y / h.w * size);  // rows top down
    const float expected = -(light.view * glm::vec4(q, 1.0f)).z;
    // A texel spans ≈ 0.03 units of a surface at ≈ 20° to the map: depth varies by 0.01.
    EXPECT_NEAR(map.image.at(x, y)[0], expected, 0.02f) << q.x << "," << q.y << "," << q.z;
  }
  EXPECT_EQ(map.image.at(0, 0)[0], 0.0f);  // the 1% margin: no caster in the corner
  bool timed = false;
  for (const auto& t : renderer.timings()) timed |= t.name == "shadowMap";
  EXPECT_TRUE(timed);
}

// Every style takes the shadow: the shadowed ground is darker than the lit ground.
class StyleShadowTest : public ::testing::TestWithParam<std::string> {};

TEST_P(StyleShadowTest, ShadowedGroundIsDarker) {
  Scene scene = boxShadowScene();
  scene.style.name = GetParam();
  Renderer renderer(scene, test::glContext().info());
  renderer.render();
  const Rgba8Image color = renderer.readColor();
  const auto aovs = renderer.readAovs();
  const FloatImage& position = findAov(aovs, "position").image;
  const FloatImage& objectId = findAov(aovs, "objectId").image;
  const glm::vec3 towardsLight = -glm::normalize(scene.lights[0].direction);
  double shadowSum = 0, litSum = 0;
  int shadowN = 0, litN = 0;
  for (int y = 0; y < scene.height; ++y)
    for (int x = 0; x < scene.width; ++x) {
      if (objectId.at(x, y)[0] != 0.0f) continue;
      const glm::vec3 p(position.at(x, y)[0], position.at(x, y)[1], position.at(x, y)[2]);
      const auto px = color.at(x, y);
      const double luminance = 0.2126 * px[0] + 0.7152 * px[1] + 0.0722 * px[2];
      if (hitsBox(p, towardsLight, glm::vec3(-0.9f, 1.6f, -0.9f), glm::vec3(0.9f, 3.4f, 0.9f)))
        shadowSum += luminance, ++shadowN;
      else if (!hitsBox(p, towardsLight, glm::vec3(-1.1f, 1.4f, -1.1f),
                        glm::vec3(1.1f, 3.6f, 1.1f)))
        litSum += luminance, ++litN;
    }
  ASSERT_GT(shadowN, 100);
  ASSERT_GT(litN, 1000);
  // Gooch's shadow is the mid tone (cool–warm halfway), the mildest of the styles.
  EXPECT_LT(shadowSum / shadowN, 0.9 * litSum / litN)
      << GetParam() << ": shadowed " << shadowSum / shadowN << ", lit " << litSum / litN;
}

INSTANTIATE_TEST_SUITE_P(Styles, StyleShadowTest,
                         ::testing::Values("gooch", "blinn-phong", "toon", "hatching"),
                         [](const auto& info) {
                           std::string n = info.param;
                           std::replace(n.begin(), n.end(), '-', '_');
                           return n;
                         });

// ---------------------------------------------------------------------------------------------
// Gooch and Blinn-Phong tone against their formulas, pixel by pixel.

namespace {

// A UV sphere of radius 1 at the origin with its analytic normals, as an OBJ file.
std::filesystem::path writeSphere() {
  const auto path = std::filesystem::temp_directory_path() /
                    ("cutaway-sphere-" + std::to_string(::getpid()) + ".obj");
  std::ofstream obj(path);
  const int rings = 48, segments = 96;
  for (int i = 0; i <= rings; ++i)
    for (int j = 0; j <= segments; ++j) {
      const double theta = M_PI * i / rings, phi = 2.0 * M_PI * j / segments;
      const glm::dvec3 p(std::sin(theta) * std::cos(phi), std::cos(theta),
                         std::sin(theta) * std::sin(phi));
      obj << "v " << p.x << " " << p.y << " " << p.z << "\nvn " << p.x << " " << p.y << " " << p.z
          << "\n";
    }
  const auto v = [&](int i, int j) { return std::to_string(i * (segments + 1) + j + 1); };
  const auto corner = [&](int i, int j) { return v(i, j) + "//" + v(i, j); };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      // Counter-clockwise seen from outside.
      if (i > 0)
        obj << "f " << corner(i, j) << " " << corner(i, j + 1) << " " << corner(i + 1, j) << "\n";
      if (i + 1 < rings)
        obj << "f " << corner(i, j + 1) << " " << corner(i + 1, j + 1) << " " << corner(i + 1, j)
            << "\n";
    }
  return path;
}

// The rendered colour at every pixel inside the sphere's image (all four neighbours on it too)
// against `formula(normal, toEye, position)`, from the AOVs of the same frame: the normal the
// shader used (half floats) and the position (floats). A formula with hard edges returns
// nothing for pixels next to one, where the half-float normal may fall either way. Returns the
// pixels compared.
int compareTone(
    const std::string& styleJson, const std::string& lightsJson,
    const std::function<std::optional<glm::vec3>(glm::vec3, glm::vec3, glm::vec3)>& formula) {
  const auto sphere = writeSphere();
  const Scene scene = parseScene(
      R"({"resolution": [96, 96], "samples": 1, "style": )" + styleJson + R"(, "lights": )" +
          lightsJson + R"(,
          "camera": {"eye": [0.6, 0.8, 4], "target": [0, 0, 0], "fov": 40},
          "objects": [{"name": "ball", "file": ")" +
          sphere.string() + R"(", "color": [0.7, 0.35, 0.2], "specular": 0.4, "shininess": 8}]})",
      "tone.json", kData);
  std::filesystem::remove(sphere);
  Renderer renderer(scene, test::glContext().info());
  renderer.render();
  const auto aovs = renderer.readAovs();
  const Rgba8Image color = renderer.readColor();
  const FloatImage &normal = findAov(aovs, "normal").image,
                   &position = findAov(aovs, "position").image,
                   &objectId = findAov(aovs, "objectId").image;
  const glm::vec3 eye = scene.resolvedCamera().eye;
  int compared = 0;
  double worst = 0.0;
  std::string where;
  for (int y = 1; y + 1 < color.height; ++y)
    for (int x = 1; x + 1 < color.width; ++x) {
      bool inside = true;
      for (const auto& [dx, dy] : {std::pair{0, 0}, {1, 0}, {-1, 0}, {0, 1}, {0, -1}})
        inside = inside && objectId.at(x + dx, y + dy)[0] == 0.0f;
      if (!inside) continue;
      const float* n = normal.at(x, y);
      const float* p = position.at(x, y);
      const glm::vec3 point(p[0], p[1], p[2]);
      const std::optional<glm::vec3> tone =
          formula(glm::normalize(glm::vec3(n[0], n[1], n[2])), glm::normalize(eye - point), point);
      if (!tone) continue;
      const glm::vec3 expected = glm::clamp(*tone, 0.0f, 1.0f);
      for (int k = 0; k < 3; ++k) {
        const double error = std::abs(color.at(x, y)[k] / 255.0 - expected[k]);
        if (error > worst) {
          worst = error;
          where = std::to_string(x) + "," + std::to_string(y) + " channel " + std::to_string(k) +
                  ": " + std::to_string(color.at(x, y)[k]) + " vs " +
                  std::to_string(expected[k] * 255.0f);
        }
      }
      ++compared;
    }
  // 8-bit rounding (½ level) plus the half-float normal's ~5e-4 through n·l and (n·h)⁸ (the
  // worst seen is 0.56 level); an ambient of 0.11 instead of 0.1 is off by 2.3 levels.
  EXPECT_LE(worst * 255.0, 1.0) << "worst pixel " << where;
  return compared;
}

float blinnSpecular(glm::vec3 n, glm::vec3 l, glm::vec3 v, float shininess) {
  if (glm::dot(n, l) <= 0.0f) return 0.0f;
  return std::pow(std::max(glm::dot(n, glm::normalize(l + v)), 0.0f), shininess);
}

}  // namespace

// Gooch et al. 1998: k_cool = k_blue + α k_d, k_warm = k_yellow + β k_d,
// I = t k_warm + (1 − t) k_cool with t = (1 + l·n)/2, from the key light; plus the white
// Blinn highlight of the key light.
TEST(StyleTone, GoochIsTheCoolToWarmBlendOfItsPaper) {
  const glm::vec3 kd(0.7f, 0.35f, 0.2f), blue(0.1f, 0.1f, 0.6f), yellow(0.5f, 0.4f, 0.0f);
  const float alpha = 0.3f, beta = 0.6f;
  const glm::vec3 travels = glm::normalize(glm::vec3(-0.5f, -0.7f, -0.3f));
  const int compared = compareTone(
      R"({"name": "gooch", "lines": false, "gooch": {"cool": [0.1, 0.1, 0.6],
          "warm": [0.5, 0.4, 0.0], "alpha": 0.3, "beta": 0.6}})",
      R"([{"type": "directional", "direction": [-0.5, -0.7, -0.3], "space": "world"},
          {"type": "point", "position": [0, -5, 0], "space": "world"}])",
      [&](glm::vec3 n, glm::vec3 v, glm::vec3) {
        const glm::vec3 l = -travels;  // the second light does not take part
        const float t = 0.5f * (1.0f + glm::dot(n, l));
        return t * (yellow + beta * kd) + (1.0f - t) * (blue + alpha * kd) +
               glm::vec3(0.4f * blinnSpecular(n, l, v, 8.0f));
      });
  EXPECT_GT(compared, 2000);
}

// Blinn-Phong: ambient k_d + Σ_lights colour (k_d max(n·l, 0) + k_s max(n·h, 0)^shininess),
// with a directional and a coloured point light (no falloff).
TEST(StyleTone, BlinnPhongSumsItsLights) {
  const glm::vec3 kd(0.7f, 0.35f, 0.2f);
  const glm::vec3 travels = glm::normalize(glm::vec3(-0.5f, -0.7f, -0.3f));
  const glm::vec3 lamp(3.0f, 1.0f, 2.0f), lampColor = glm::vec3(0.2f, 0.5f, 0.9f) * 0.8f;
  const int compared = compareTone(
      R"({"name": "blinn-phong", "lines": false, "blinnPhong": {"ambient": 0.1}})",
      R"([{"type": "directional", "direction": [-0.5, -0.7, -0.3], "space": "world"},
          {"type": "point", "position": [3, 1, 2], "space": "world", "color": [0.2, 0.5, 0.9],
           "intensity": 0.8}])",
      [&](glm::vec3 n, glm::vec3 v, glm::vec3 p) {
        glm::vec3 c = 0.1f * kd;
        const glm::vec3 l0 = -travels, l1 = glm::normalize(lamp - p);
        c += kd * std::max(glm::dot(n, l0), 0.0f) + glm::vec3(0.4f * blinnSpecular(n, l0, v, 8.0f));
        c += lampColor *
             (kd * std::max(glm::dot(n, l1), 0.0f) + 0.4f * blinnSpecular(n, l1, v, 8.0f));
        return c;
      });
  EXPECT_GT(compared, 2000);
}

// Toon (Lake00 §3.1): the ramp's tone of the key light's max(n·l, 0) (equal bands, 8-bit
// texels) times the object colour, plus the object's specular times the highlight colour where
// the Blinn term (n·h)^shininess passes the threshold. Pixels within 0.02 of a band edge (in
// units of n·l) or of the threshold are left out; the highlight must cover some pixels and
// leave others.
TEST(StyleTone, ToonIsTheRampsBandPlusTheHardHighlight) {
  const glm::vec3 kd(0.7f, 0.35f, 0.2f), highlight(0.9f, 0.8f, 1.0f);
  const std::vector<glm::vec3> ramp{glm::vec3(0.2f), glm::vec3(0.5f, 0.55f, 0.6f), glm::vec3(1.0f)};
  const float threshold = 0.6f;
  const glm::vec3 travels = glm::normalize(glm::vec3(-0.5f, -0.7f, -0.3f));
  int highlighted = 0, plain = 0;
  const int compared = compareTone(
      R"({"name": "toon", "lines": false,
          "toon": {"ramp": [0.2, [0.5, 0.55, 0.6], 1], "highlight": true,
                   "highlightThreshold": 0.6, "highlightColor": [0.9, 0.8, 1.0]}})",
      R"([{"type": "directional", "direction": [-0.5, -0.7, -0.3], "space": "world"}])",
      [&](glm::vec3 n, glm::vec3 v, glm::vec3) -> std::optional<glm::vec3> {
        const glm::vec3 l = -travels;
        const float nDotL = std::max(glm::dot(n, l), 0.0f), bands = float(ramp.size());
        const float edge = std::round(nDotL * bands) / bands;
        if (nDotL > 0.0f && edge > 0.0f && edge < 1.0f && std::abs(nDotL - edge) < 0.02f)
          return std::nullopt;
        const float blinn = blinnSpecular(n, l, v, 8.0f);
        if (std::abs(blinn - threshold) < 0.02f) return std::nullopt;
        const glm::vec3 texel =
            glm::round(ramp[toonRampIndex(int(ramp.size()), nDotL)] * 255.0f) / 255.0f;
        glm::vec3 c = texel * kd;
        if (blinn > threshold)
          c += 0.4f * highlight, ++highlighted;
        else
          ++plain;
        return glm::min(c, glm::vec3(1.0f));
      });
  EXPECT_GT(compared, 1500);
  EXPECT_GT(highlighted, 30);
  EXPECT_GT(plain, 1000);
}

namespace {

// A line in pixels (rows top down).
using Segment = std::pair<glm::vec2, glm::vec2>;

// Where the scene's camera shows world point p, in pixels of its frame (rows top down).
glm::vec2 projectToPixel(const Scene& scene, const glm::vec3& p) {
  const Camera camera = scene.resolvedCamera();
  const glm::vec4 c = camera.projectionMatrix(float(scene.width) / float(scene.height)) *
                      camera.view() * glm::vec4(p, 1.0f);
  return glm::vec2((c.x / c.w + 1.0f) * 0.5f * float(scene.width),
                   (1.0f - c.y / c.w) * 0.5f * float(scene.height));
}

// The edges of the unit cube centred at `center` that the eye sees (a face beside each faces
// it): its twelve edges, each with the outward normals of its two faces.
std::vector<std::pair<glm::vec3, glm::vec3>> visibleCubeEdges(glm::vec3 eye, glm::vec3 center) {
  std::vector<std::pair<glm::vec3, glm::vec3>> visible;
  for (int axis = 0; axis < 3; ++axis)
    for (const float s : {-0.5f, 0.5f})
      for (const float t : {-0.5f, 0.5f}) {
        glm::vec3 a(0.0f), n1(0.0f), n2(0.0f);
        const int i = (axis + 1) % 3, j = (axis + 2) % 3;
        a[i] = s, a[j] = t, n1[i] = s > 0 ? 1.0f : -1.0f, n2[j] = t > 0 ? 1.0f : -1.0f;
        glm::vec3 b = a;
        a[axis] = -0.5f, b[axis] = 0.5f;
        a += center, b += center;
        const glm::vec3 mid = 0.5f * (a + b);
        if (glm::dot(n1, eye - mid) > 0.0f || glm::dot(n2, eye - mid) > 0.0f)
          visible.push_back({a, b});
      }
  return visible;
}

struct LinesFound {
  int linePixels = 0, points = 0, drawn = 0;
};

// The points every half pixel along `expected`, `inset` px in from their ends, and those
// within a pixel of a line pixel.
LinesFound pointsDrawn(const FloatImage& lines, const std::vector<Segment>& expected, float inset) {
  LinesFound found;
  for (const Segment& e : expected) {
    const float length = glm::length(e.second - e.first);
    for (float s = inset; s <= length - inset; s += 0.5f) {
      const glm::vec2 p = e.first + (s / length) * (e.second - e.first);
      bool near = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int x = int(p.x) + dx, y = int(p.y) + dy;
          near = near || (x >= 0 && y >= 0 && x < lines.width && y < lines.height &&
                          lines.at(x, y)[0] >= 0.5f);
        }
      ++found.points, found.drawn += near;
    }
  }
  return found;
}

// The lines AOV against the lines expected: every line pixel within 1.5 px of one (each
// other is reported), and the points every half pixel along them, `inset` px in from their
// ends, within a pixel of a line pixel. Returns the line pixels, the points and those drawn.
LinesFound expectLinesAlong(const FloatImage& lines, const std::vector<Segment>& expected,
                            float inset) {
  const auto distance = [](glm::vec2 p, const Segment& e) {
    const glm::vec2 d = e.second - e.first;
    const float t = glm::clamp(glm::dot(p - e.first, d) / glm::dot(d, d), 0.0f, 1.0f);
    return glm::length(p - (e.first + t * d));
  };
  LinesFound found;
  for (int y = 0; y < lines.height; ++y)
    for (int x = 0; x < lines.width; ++x) {
      if (lines.at(x, y)[0] < 0.5f) continue;
      ++found.linePixels;
      float nearest = 1e30f;
      for (const Segment& e : expected)
        nearest = std::min(nearest, distance({x + 0.5f, y + 0.5f}, e));
      if (nearest > 1.5f)
        ADD_FAILURE() << "line pixel " << x << "," << y << " is " << nearest
                      << " px from the nearest expected line";
    }
  const LinesFound along = pointsDrawn(lines, expected, inset);
  found.points = along.points, found.drawn = along.drawn;
  return found;
}

}  // namespace

// Silhouettes and creases (the image-space lines of frame/lines) against a CPU classification
// of a cube's edges seen by the same camera: an edge is drawn when a face beside it faces the
// eye (a silhouette if the other does not, a crease of 90° > the 45° crease angle if it
// does). Every line pixel lies within 1.5 pixels of such an edge projected, and such edges are
// drawn along their length (away from the corners).
TEST(LineRender, ACubesLinesAreItsVisibleEdges) {
  const Scene scene = parseScene(
      R"({"resolution": [128, 128], "samples": 1, "background": [1, 1, 1],
      "style": {"name": "gooch", "lines": {"silhouettes": true, "creases": true,
                                           "creaseAngle": 45, "width": 1}},
      "camera": {"eye": [2.2, 1.7, 3.0], "target": [0, 0, 0], "fov": 35},
      "objects": [{"name": "cube", "file": "meshes/cube.obj",
                   "transform": {"translate": [-0.5, -0.5, -0.5]}}]})",
      "lines.json", kData);
  Renderer renderer(scene, test::glContext().info());
  renderer.render();
  const auto aovs = renderer.readAovs();
  const FloatImage& lines = findAov(aovs, "lines").image;  // rows top down
  std::vector<Segment> visible;
  for (const auto& [a, b] : visibleCubeEdges(scene.resolvedCamera().eye, glm::vec3(0.0f)))
    visible.push_back({projectToPixel(scene, a), projectToPixel(scene, b)});
  ASSERT_EQ(visible.size(), 9u);  // three faces seen: six silhouette and three crease edges
  // Away from the corners, where the lines of two edges meet.
  const LinesFound found = expectLinesAlong(lines, visible, 3.0f);
  EXPECT_GT(found.linePixels, 300);
  EXPECT_GE(found.drawn, found.points * 98 / 100)
      << found.drawn << " of " << found.points << " edge points drawn";
}

// A cube standing on the ground, seen from 170 units away: at the cube's base the ground and
// its walls lie within a hundredth of a unit of each other, less than a depth margin would be,
// but they meet at 90° (more than the crease angle), so the base is drawn as the cube's other
// edges are, along its length.
// Its lines against the CPU's visible edges, as ACubesLinesAreItsVisibleEdges.
TEST(LineRender, AnObjectStandingOnAnotherMeetsItInAContinuousLine) {
  const Scene scene = parseScene(
      R"({"resolution": [128, 128], "samples": 1, "background": [1, 1, 1],
      "style": {"name": "gooch", "lines": {"silhouettes": true, "creases": true,
                                           "creaseAngle": 45, "width": 1}},
      "camera": {"eye": [112, 75, 105], "target": [0, 0, 0.4], "up": [0, 0, 1], "fov": 1},
      "objects": [{"name": "ground", "file": "render/plane.obj"},
                  {"name": "cube", "file": "meshes/cube.obj",
                   "transform": {"translate": [-0.5, -0.5, 0]}}]})",
      "standing.json", kData);
  const auto aovs = test::renderAovs(scene);
  const FloatImage& lines = test::aov(aovs, "lines");  // rows top down
  std::vector<Segment> visible, base;
  for (const auto& [a, b] :
       visibleCubeEdges(scene.resolvedCamera().eye, glm::vec3(0.0f, 0.0f, 0.5f))) {
    const Segment e{projectToPixel(scene, a), projectToPixel(scene, b)};
    visible.push_back(e);
    if (a.z == 0.0f && b.z == 0.0f) base.push_back(e);
  }
  ASSERT_EQ(visible.size(), 9u);
  ASSERT_EQ(base.size(), 2u);  // the two bottom edges in sight
  const LinesFound all = expectLinesAlong(lines, visible, 3.0f);
  EXPECT_GT(all.linePixels, 300);
  const LinesFound contact = pointsDrawn(lines, base, 3.0f);
  EXPECT_GT(contact.points, 100);
  EXPECT_GE(contact.drawn, contact.points * 98 / 100)
      << contact.drawn << " of " << contact.points << " points of the base drawn";
}

// Coplanar objects draw no line between them, however their depth test ties and though their
// shading normals differ a little: a door a hair (1e-4 units, 1e-5 of the depth) in front of
// its wall, seen head-on, its normal tilted by 3°, is drawn without a line round it.
TEST(LineRender, CoplanarObjectsDrawNoLineBetweenThem) {
  const Scene scene = parseScene(
      R"({"resolution": [96, 96], "samples": 4, "background": [1, 1, 1],
      "style": {"name": "gooch", "lines": {"silhouettes": true, "creases": true, "width": 1}},
      "camera": {"eye": [0, 0, 12], "target": [0, 0, 0], "fov": 40},
      "objects": [{"name": "wall", "file": "render/plane.obj"},
                  {"name": "door", "file": "render/plane_tilted_normals.obj",
                   "transform": {"translate": [0, 0, 1e-4], "scale": 0.2}}]})",
      "flush.json", kData);
  const auto aovs = test::renderAovs(scene);
  const FloatImage &lines = test::aov(aovs, "lines"), &id = test::aov(aovs, "objectId");
  int door = 0, drawn = 0;
  for (int y = 0; y < lines.height; ++y)
    for (int x = 0; x < lines.width; ++x)
      door += id.at(x, y)[0] == 1.0f, drawn += lines.at(x, y)[0] > 0.0f;
  EXPECT_GT(door, 100);  // the door shows
  EXPECT_EQ(drawn, 0);
}

// The same against a smooth surface: a capped cylinder (radius ½, y ∈ [−0.6, 0.6], 96 sides
// with smooth normals, flat caps) seen from above at a slant. Its lines, worked out on the CPU:
// the two silhouette generators, where the side's normal n = (cos φ, 0, sin φ) is at right
// angles to the view (E_x cos φ + E_z sin φ = ½); the top rim all round (the cap faces the
// eye: a 90° crease in front, a silhouette behind); the bottom rim between the generators, on
// the near side (the side faces the eye, the bottom does not). Nothing else: the side's
// facets meet at 3.75°, under the 45° crease angle, and fold away from the eye smoothly.
TEST(LineRender, ACylindersLinesAreItsRimsAndSilhouetteGenerators) {
  const std::filesystem::path obj = std::filesystem::temp_directory_path() /
                                    ("cutaway-cylinder-" + std::to_string(::getpid()) + ".obj");
  constexpr int kSides = 96;
  constexpr float kR = 0.5f, kH = 0.6f;
  {
    std::ofstream out(obj);
    for (int i = 0; i < kSides; ++i) {
      const float phi = 2.0f * glm::pi<float>() * float(i) / kSides;
      out << "v " << kR * std::cos(phi) << " " << -kH << " " << kR * std::sin(phi) << "\n"
          << "v " << kR * std::cos(phi) << " " << kH << " " << kR * std::sin(phi) << "\n"
          << "vn " << std::cos(phi) << " 0 " << std::sin(phi) << "\n";
    }
    out << "vn 0 1 0\nvn 0 -1 0\n";
    for (int i = 0; i < kSides; ++i) {
      const int a = 2 * i + 1, b = 2 * i + 2, c = 2 * ((i + 1) % kSides) + 1, d = c + 1;
      const int na = i + 1, nc = (i + 1) % kSides + 1;
      out << "f " << a << "//" << na << " " << b << "//" << na << " " << d << "//" << nc << "\n"
          << "f " << a << "//" << na << " " << d << "//" << nc << " " << c << "//" << nc << "\n";
      if (i > 0 && i + 1 < kSides) {  // the caps as fans
        out << "f 2//" << kSides + 1 << " " << d << "//" << kSides + 1 << " " << b << "//"
            << kSides + 1 << "\n";
        out << "f 1//" << kSides + 2 << " " << a << "//" << kSides + 2 << " " << c << "//"
            << kSides + 2 << "\n";
      }
    }
  }
  const glm::vec3 eye(2.4f, 1.6f, 3.0f);
  const Scene scene = parseScene(
      R"({"resolution": [128, 128], "samples": 1, "background": [1, 1, 1],
      "style": {"name": "gooch", "lines": {"silhouettes": true, "creases": true,
                                           "creaseAngle": 45, "width": 1}},
      "camera": {"eye": [2.4, 1.6, 3.0], "target": [0, 0, 0], "fov": 35},
      "objects": [{"name": "cylinder", "file": ")" +
          obj.string() + R"("}]})",
      "cylinder.json", kData);
  Renderer renderer(scene, test::glContext().info());
  renderer.render();
  std::filesystem::remove(obj);
  const auto aovs = renderer.readAovs();
  const FloatImage& lines = findAov(aovs, "lines").image;  // rows top down
  const auto pixel = [&](glm::vec3 p) { return projectToPixel(scene, p); };
  const auto onCircle = [&](float phi, float y) {
    return glm::vec3(kR * std::cos(phi), y, kR * std::sin(phi));
  };
  // E_x cos φ + E_z sin φ = R: φ = atan2(E_z, E_x) ± acos(R / |E_xz|).
  const float towardsEye = std::atan2(eye.z, eye.x);
  const float spread = std::acos(kR / glm::length(glm::vec2(eye.x, eye.z)));
  std::vector<Segment> expected;
  for (const float phi : {towardsEye - spread, towardsEye + spread})
    expected.push_back({pixel(onCircle(phi, -kH)), pixel(onCircle(phi, kH))});
  constexpr int kSteps = 720;
  for (int k = 0; k < kSteps; ++k) {
    const float a = 2.0f * glm::pi<float>() * float(k) / kSteps,
                b = 2.0f * glm::pi<float>() * float(k + 1) / kSteps;
    expected.push_back({pixel(onCircle(a, kH)), pixel(onCircle(b, kH))});
    const float sa = towardsEye - spread + 2.0f * spread * float(k) / kSteps,
                sb = towardsEye - spread + 2.0f * spread * float(k + 1) / kSteps;
    expected.push_back({pixel(onCircle(sa, -kH)), pixel(onCircle(sb, -kH))});
  }
  const LinesFound found = expectLinesAlong(lines, expected, 0.0f);
  std::printf("cylinder: %d line pixels; %d of %d expected points drawn\n", found.linePixels,
              found.drawn, found.points);
  EXPECT_GT(found.linePixels, 200);
  EXPECT_GE(found.drawn, found.points * 98 / 100) << found.drawn << " of " << found.points;
}

// Hatching tone (Praun01 §4): the key light's Lambert lightness L gives the darkness 1 − L,
// the tone position u = (1 − L)·tones − 1 between the two bracketing TAM tones, and the ink
// their blend. A plane facing the camera under a light at n·l = L, seen orthographically so
// that the view spans exactly one hatch tile at the finest mipmap level (256 pixels): the
// image's mean ink is the blend of the two tones' mean ink in the CPU-built TAM.
TEST(StyleTone, HatchingInkIsTheTamsBlendForTheLightness) {
  const TonalArtMap& tam = defaultTam();  // the style's: 6 tones, seed 1
  ASSERT_EQ(HatchingStyle{}.seed, 1u);
  ASSERT_EQ(HatchingStyle{}.tones, tam.tones);
  const HatchingStyle defaults;
  for (const float lightness : {0.85f, 0.5f, 0.2f}) {
    const glm::vec3 towardsLight(std::sqrt(1.0f - lightness * lightness), 0.0f, lightness);
    char json[900];
    std::snprintf(json, sizeof json,
                  R"({"resolution": [256, 256], "samples": 1, "background": [1, 1, 1],
                      "style": {"name": "hatching", "lines": false, "hatching": {"tint": 0}},
                      "lights": [{"type": "directional", "direction": [%g, %g, %g], "space": "world"}],
                      "camera": {"projection": "orthographic", "height": 8, "eye": [0, 0, 10],
                                 "target": [0, 0, 0]},
                      "objects": [{"name": "plane", "file": "render/plane.obj"}]})",
                  -towardsLight.x, -towardsLight.y, -towardsLight.z);
    Scene scene = parseScene(json, "hatch.json", kData);
    // One tile (scale × the scene's radius) across the 8-unit view.
    scene.style.edit<HatchingStyle>().scale = 8.0f / scene.bounds().radius();
    Renderer renderer(scene, test::glContext().info());
    renderer.render();
    const Rgba8Image color = renderer.readColor();
    double sum = 0.0;
    for (std::size_t i = 0; i < color.pixels.size(); i += 4) sum += color.pixels[i] / 255.0;
    const double mean = sum / (double(color.width) * color.height);
    const double ink = (defaults.paper.r - mean) / (defaults.paper.r - defaults.ink.r);
    const double u = (1.0 - lightness) * tam.tones - 1.0, lower = std::floor(u), w = u - lower;
    const double inkLower = lower < 0.0 ? 0.0 : tam.meanInk(0, int(lower));
    const double inkUpper = tam.meanInk(0, std::min(int(lower) + 1, tam.tones - 1));
    const double expected = (1.0 - w) * inkLower + w * inkUpper;
    // 8-bit colours and bilinear filtering of the tile, which keeps its mean (agreement was
    // to 1e-4 when this was written).
    EXPECT_NEAR(ink, expected, 0.003) << "lightness " << lightness;
    std::printf("lightness %.2f: mean ink %.4f, the TAM's blend %.4f\n", lightness, ink, expected);
  }
}

// Hatching's texture coordinates (src/styles/hatching/hatching.glsl): three planar projections
// of the world position (x: zy, y: xz, z: xy) in tiles, weighted by |n|⁸ normalised. A plane
// tilted to n ∝ (0.45, 0.55, 0.7) and seen face-on, four pixels per TAM texel (the finest
// level, bilinear): each pixel's colour against the paper and ink mixed by Σ wᵢ·(the TAM's two
// tones for its darkness, blended) read at each projection, from the AOVs' position and
// normal and the TAM's 8-bit texels.
TEST(StyleTone, HatchingProjectsItsStrokesThreeWaysWeightedByTheNormal) {
  const TonalArtMap& tam = defaultTam();
  const HatchingStyle defaults;
  const glm::vec3 n = glm::normalize(glm::vec3(0.45f, 0.55f, 0.7f));
  const glm::vec3 axis = glm::normalize(glm::cross(glm::vec3(0, 0, 1), n));
  const float degrees = glm::degrees(std::acos(n.z));
  const glm::vec3 l = glm::normalize(n + glm::vec3(0.6f, -0.5f, 0.1f));  // towards the light
  char json[1200];
  std::snprintf(json, sizeof json,
                R"({"resolution": [128, 128], "samples": 1, "background": [1, 1, 1],
                    "style": {"name": "hatching", "lines": false, "hatching": {"tint": 0}},
                    "lights": [{"type": "directional", "direction": [%g, %g, %g], "space": "world"}],
                    "camera": {"projection": "orthographic", "height": 1, "eye": [%g, %g, %g],
                               "target": [0, 0, 0], "up": [0, 0, 1]},
                    "objects": [{"name": "plane", "file": "render/plane.obj",
                                 "transform": {"rotate": {"axis": [%g, %g, %g], "degrees": %g}}}]})",
                -l.x, -l.y, -l.z, 5 * n.x, 5 * n.y, 5 * n.z, axis.x, axis.y, axis.z, degrees);
  Scene scene = parseScene(json, "hatch-triplanar.json", kData);
  // A tile of 8 units: 32 texels per unit, 4 pixels per texel face-on.
  scene.style.edit<HatchingStyle>().scale = 8.0f / scene.bounds().radius();
  Renderer renderer(scene, test::glContext().info());
  renderer.render();
  const Rgba8Image color = renderer.readColor();
  const auto aovs = renderer.readAovs();
  const FloatImage &position = findAov(aovs, "position").image,
                   &normal = findAov(aovs, "normal").image;
  // The finest level's ink of `tone` as the GPU holds it (R8), bilinear with repeat.
  const auto ink = [&](int tone, glm::vec2 uv) {
    const std::vector<float>& texels = tam.ink(0, tone);
    const int size = tam.width(0);
    const auto texel = [&](int x, int y) {
      x = ((x % size) + size) % size, y = ((y % size) + size) % size;
      return std::round(std::clamp(texels[std::size_t(y) * size + x], 0.0f, 1.0f) * 255.0f) /
             255.0f;
    };
    const glm::vec2 at = uv * float(size) - 0.5f;
    const glm::ivec2 i(glm::floor(at));
    const glm::vec2 f = at - glm::vec2(i);
    return glm::mix(glm::mix(texel(i.x, i.y), texel(i.x + 1, i.y), f.x),
                    glm::mix(texel(i.x, i.y + 1), texel(i.x + 1, i.y + 1), f.x), f.y);
  };
  double worst = 0.0, sum = 0.0;
  int pixels = 0;
  for (int y = 0; y < color.height; ++y)
    for (int x = 0; x < color.width; ++x) {
      const glm::vec3 p = glm::make_vec3(position.at(x, y));
      const glm::vec3 m = glm::normalize(glm::make_vec3(normal.at(x, y)));
      const float darkness = std::clamp(1.0f - std::max(glm::dot(m, l), 0.0f), 0.0f, 1.0f);
      const float u = darkness * float(tam.tones) - 1.0f, lower = std::floor(u), w = u - lower;
      const auto blend = [&](glm::vec2 uv) {
        const float a = lower < 0.0f ? 0.0f : ink(int(lower), uv);
        return glm::mix(a, ink(std::min(int(lower) + 1, tam.tones - 1), uv), w);
      };
      glm::vec3 weights = glm::pow(glm::abs(m), glm::vec3(8.0f));
      weights /= weights.x + weights.y + weights.z;
      const glm::vec3 q = p / 8.0f;  // tile units
      const float coverage = weights.x * blend({q.z, q.y}) + weights.y * blend({q.x, q.z}) +
                             weights.z * blend({q.x, q.y});
      const glm::vec3 expected = glm::mix(defaults.paper, defaults.ink, coverage);
      for (int k = 0; k < 3; ++k) {
        const double e = std::abs(color.at(x, y)[k] - 255.0 * expected[k]);
        worst = std::max(worst, e);
        sum += e;
      }
      ++pixels;
    }
  std::printf("hatching triplanar: %d pixels, darkness %.2f, mean %.2f, worst %.2f levels\n",
              pixels, 1.0f - glm::dot(n, l), sum / (3.0 * pixels), worst);
  // 8-bit output and the GPU's 8-bit filter weights (measured: mean 0.3, worst 1.4).
  EXPECT_LT(sum / (3.0 * pixels), 0.6);
  EXPECT_LE(worst, 2.5);
}
