// Occlusion reduction applied as translucency, edge highlights and lines (Burns11 ch. 2, eqs.
// 2.1–2.2, §2.3) through the contextual structure's R, composited by depth peeling
// (frame/translucent_layers.hpp): every pixel of a stack of three tilted squares against the
// closed form, front-to-back "over" of each square's own colour with its opacity computed on
// the CPU from the dumped cutaway surfaces (eqs. 5.6, 7.1–7.3, 2.1–2.2); a layer budget below
// the depth complexity against the same closed form cut short; a square in the overlay drawn
// as its uncut outline faded by R.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

#define GLM_ENABLE_EXPERIMENTAL
#include <glm/gtx/string_cast.hpp>

#include "cutaway/cutters/adaptive.hpp"
#include "cutaway/render/renderer.hpp"
#include "render_aovs.hpp"

using namespace cutaway;

namespace {

const std::string kData = CUTAWAY_TEST_DATA;
constexpr int kSize =
    128;  // the image's and the cutaway buffer's: a pixel centre is a texel centre
constexpr float kInvisible = 1.0f / 512.0f;  // mesh.frag's: no layer for less opacity

struct Square {
  const char* name;
  float z;        // centre on the view axis
  float tiltDeg;  // about the y axis
  float importance;
  glm::vec3 color;
};
// Nearest first at the centre (tilted, they cross); seen from +z by an orthographic camera at
// z = 10.
const Square kSquares[3] = {{"near", 1.0f, 25.0f, 0.2f, {0.9f, 0.3f, 0.2f}},
                            {"middle", 0.0f, -15.0f, 0.5f, {0.2f, 0.7f, 0.3f}},
                            {"far", -1.0f, 35.0f, 0.8f, {0.2f, 0.3f, 0.9f}}};

std::string squareJson(const Square& s) {
  return std::string(R"({"name": ")") + s.name + R"(", "file": "plane.obj", "color": [)" +
         std::to_string(s.color.r) + "," + std::to_string(s.color.g) + "," +
         std::to_string(s.color.b) + R"(], "specular": 0, "importance": )" +
         std::to_string(s.importance) + R"(, "transform": {"translate": [0, 0, )" +
         std::to_string(s.z) + R"(], "rotate": [0, )" + std::to_string(s.tiltDeg) +
         R"(, 0], "scale": 0.6}})";
}

// The squares, cut around an invisible box far behind them by a contextual cutaway applied as
// `apply`; or one square alone (`only`). Blinn-Phong under a light along the view:
// each square's colour is uniform (orthographic view, flat square).
Scene stackScene(const std::string& apply, int layers, int only = -1) {
  std::string objects;
  for (int k = 0; k < 3; ++k) {
    if (only >= 0 && k != only) continue;
    objects += (objects.empty() ? "" : ",") + squareJson(kSquares[k]);
  }
  const std::string size = std::to_string(kSize);
  return parseScene(R"({
      "resolution": [)" +
                        size + "," + size + R"(], "samples": 1,
      "style": {"name": "blinn-phong", "lines": false},
      "lights": [{"type": "directional", "direction": [0, 0, -1], "space": "camera"}],
      "camera": {"projection": "orthographic", "eye": [0, 0, 10], "target": [0, 0, 0],
                 "height": 10, "near": 1, "far": 30},
      "objects": [)" + objects +
                        R"(],
      "proxies": [{"name": "roi", "box": {"min": [-1, -1, -6], "max": [1, 1, -4]},
                   "role": "interest"}],
      "cutters": {"adaptive": {"angle": 30, "bufferSize": )" +
                        size + R"(, "outlines": false,
          "perspectiveCompensation": false, "edgeCompression": false,
          "contextual": {"transitionAngle": 60, "overlay": 1.5, "reduction": "importance",
                         "apply": ")" +
                        apply + R"(", "edgeExponent": 2, "layers": )" + std::to_string(layers) +
                        R"(}}}})",
                    "translucent-stack.json", kData + "/render");
}

glm::vec3 rgb(const Rgba8Image& image, int x, int y) {
  const auto* p = image.at(x, y);
  return glm::vec3(p[0], p[1], p[2]) / 255.0f;
}

// View distance of window depth `c` (orthographic: linear, the same for every pixel).
float viewDistance(const glm::mat4& inverseProjection, float c) {
  const glm::vec4 h = inverseProjection * glm::vec4(0.0f, 0.0f, 2.0f * c - 1.0f, 1.0f);
  return -h.z / h.w;
}

struct Expected {
  glm::vec3 color;
  bool smooth;       // away from a square's border, where two cross, and where a fate may round
                     // either way
  bool translucent;  // a partly transparent square shows here
};

// A kSize² image of window depths (rows top-down) sampled bilinearly at a window position
// (pixels, y up), as the GPU's linear filter does.
float bilinear(const FloatImage& image, glm::vec2 window) {
  const glm::vec2 t = window - 0.5f;
  const glm::ivec2 i = glm::ivec2(glm::floor(t));
  const glm::vec2 f = t - glm::vec2(i);
  const auto at = [&](int x, int y) {
    x = std::clamp(x, 0, kSize - 1), y = std::clamp(y, 0, kSize - 1);
    return *image.at(x, kSize - 1 - y);
  };
  return glm::mix(glm::mix(at(i.x, i.y), at(i.x + 1, i.y), f.x),
                  glm::mix(at(i.x, i.y + 1), at(i.x + 1, i.y + 1), f.x), f.y);
}

// The closed form at every pixel: the squares' opacities from the cutaway surfaces dumped by
// the full scene (eqs. 5.6, 7.1–7.3, 2.1–2.2), composited front to back in their order along
// the ray over the white background, the first `layers` peeled ones only. The opaque pass
// keeps what is opaque at the pixel centre; the rest is peeled, with its opacity at the sample.
std::vector<Expected> closedForm(ContextualCutawayOptions::Application apply,
                                 const std::vector<Aov>& aovs, const Scene& scene,
                                 const glm::vec3 colors[3], int layers) {
  const FloatImage &c1 = test::aov(aovs, "cutawayDepth"), &c2 = test::aov(aovs, "cutawayDepthC2");
  const glm::mat4 inverse = glm::inverse(scene.resolvedCamera().projectionMatrix(1.0f));
  const float d = *scene.cutters.find<AdaptiveCutawayOptions>()->contextual->overlay;
  // The layers are shaded per sample; at one sample the frame's targets are 2-D textures
  // (TargetDesc::samples), whose sample is the pixel centre.
  const glm::vec2 sample(0.5f);
  // Square k's opacity at window position w (the view spans [−5, 5]²), and its height there.
  const auto opacity = [&](int k, glm::vec2 w, float& wz) {
    const Square& s = kSquares[k];
    const float t = glm::radians(s.tiltDeg);
    const float wx = -5.0f + 10.0f * w.x / kSize;
    wz = s.z - std::tan(t) * wx;  // the plane: normal (sin t, 0, cos t) through (0, 0, z)
    const float z1 = viewDistance(inverse, bilinear(c1, w));
    const ContextualRay ray{z1, std::max(viewDistance(inverse, bilinear(c2, w)), z1), d, 0.5f};
    const float r = occlusionReduction(contextualOcclusion(ray, 10.0f - wz), s.importance);
    return reducedOpacity(apply, r, std::cos(t), 2.0f).x;
  };
  std::vector<Expected> out;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const glm::vec2 centre(x + 0.5f, kSize - 1 - y + 0.5f), atSample(centre - 0.5f + sample);
      const float wx = -5.0f + 10.0f * centre.x / kSize, wy = -5.0f + 10.0f * centre.y / kSize;
      struct Hit {
        float z, alpha;
        int square;
        bool peeled;  // left to the layers by the opaque pass
      };
      std::vector<Hit> hits;
      Expected e{glm::vec3(0.0f), true, false};
      for (int k = 0; k < 3; ++k) {
        const float u = std::abs(wx / std::cos(glm::radians(kSquares[k].tiltDeg)));  // half side 6
        if (std::abs(u - 6.0f) < 0.2f || std::abs(std::abs(wy) - 6.0f) < 0.2f) e.smooth = false;
        if (u > 6.0f || std::abs(wy) > 6.0f) continue;
        // A fragment's fate (kept by the opaque pass, peeled, or too faint for a layer) may
        // fall either way where it changes within a twentieth of a pixel, as compare() allows.
        const auto fateChanges = [&](glm::vec2 w, auto fate) {
          float z;
          const bool here = fate(opacity(k, w, z));
          for (const glm::vec2 step : {glm::vec2(0.05f, 0), glm::vec2(-0.05f, 0),
                                       glm::vec2(0, 0.05f), glm::vec2(0, -0.05f)})
            if (fate(opacity(k, w + step, z)) != here) return true;
          return false;
        };
        const auto opaqueFate = [](float a) { return a >= 1.0f; };
        const auto layerFate = [](float a) { return a > kInvisible; };
        if (fateChanges(centre, opaqueFate) || fateChanges(atSample, layerFate)) e.smooth = false;
        float wz;
        const float opaque = opacity(k, centre, wz);
        if (opaque >= 1.0f) {
          hits.push_back({wz, 1.0f, k, false});
          continue;
        }
        const float alpha = opacity(k, atSample, wz);
        hits.push_back({wz, std::min(alpha, 1.0f), k, true});
      }
      std::sort(hits.begin(), hits.end(), [](const Hit& a, const Hit& b) { return a.z > b.z; });
      for (std::size_t i = 1; i < hits.size(); ++i)
        if (hits[i - 1].z - hits[i].z < 0.05f) e.smooth = false;
      float transmitted = 1.0f;
      int translucent = 0;
      for (const Hit& h : hits) {
        if (h.alpha <= kInvisible) continue;
        if (h.peeled) {
          if (++translucent > layers) continue;
          e.translucent = e.translucent || (transmitted > 0.0f && h.alpha < 1.0f);
        }
        e.color += transmitted * h.alpha * colors[h.square];
        transmitted *= 1.0f - h.alpha;
      }
      e.color += transmitted * glm::vec3(1.0f);
      out.push_back(e);
    }
  return out;
}

struct Comparison {
  int checked = 0, over = 0;  // pixels compared; of them, off by more than the tolerance
  double meanError = 0;       // per channel, in [0, 1]
  double maxError = 0;        // the largest error in units of its pixel's tolerance
  double maxAbsolute = 0;     // the largest error, in [0, 1]
  std::string worst;          // that pixel, its colour and the closed form's
};

// Within 8-bit rounding of the result and of the squares' colours (2/255), plus a twentieth
// of the closed form's change across a pixel: on the steep ramps (R goes from 0 to 1 in a few
// pixels) a twentieth of a pixel in the sample's position or the texture filter's weights moves
// the colour by that much.
Comparison compare(const Rgba8Image& image, const std::vector<Expected>& expected) {
  const auto at = [&](int x, int y) {
    x = std::clamp(x, 0, kSize - 1), y = std::clamp(y, 0, kSize - 1);
    return expected[std::size_t(y) * kSize + std::size_t(x)].color;
  };
  Comparison c;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const Expected& e = expected[std::size_t(y) * kSize + std::size_t(x)];
      if (!e.smooth) continue;
      const glm::vec3 got = rgb(image, x, y);
      const glm::vec3 change =
          glm::max(glm::abs(at(x + 1, y) - at(x - 1, y)), glm::abs(at(x, y + 1) - at(x, y - 1))) *
          0.5f;
      double pixelError = 0;  // in units of the tolerance
      for (int k = 0; k < 3; ++k) {
        const double error = std::abs(got[k] - e.color[k]);
        c.meanError += error;
        c.maxAbsolute = std::max(c.maxAbsolute, error);
        pixelError = std::max(pixelError, error / (2.0 / 255.0 + 0.05 * change[k]));
      }
      c.over += pixelError > 1.0;
      if (pixelError > c.maxError) {
        c.maxError = pixelError;
        c.worst = "pixel " + std::to_string(x) + "," + std::to_string(y) + ": " +
                  glm::to_string(got * 255.0f) + ", closed form " +
                  glm::to_string(e.color * 255.0f);
      }
      ++c.checked;
    }
  c.meanError /= 3.0 * std::max(c.checked, 1);
  return c;
}

// Each square's colour: the square alone and uncut, at the image's centre.
glm::vec3 squareColor(int k) {
  Scene scene = stackScene("cut", 1, k);
  scene.cutters.clear();
  Renderer renderer(scene, test::glContext().info());
  renderer.render();
  return rgb(renderer.readColor(), kSize / 2, kSize / 2);
}

}  // namespace

class TranslucentStack : public ::testing::TestWithParam<ContextualCutawayOptions::Application> {
 protected:
  // The stack rendered with `layers` peeled at most; the closed form for `assumed` layers.
  struct Run {
    Rgba8Image image;
    std::vector<Aov> aovs;
    Scene scene;
  };
  Run render(int layers) const {
    const bool translucency = GetParam() == ContextualCutawayOptions::Application::Translucency;
    Run run{{}, {}, stackScene(translucency ? "translucency" : "edgeHighlights", layers)};
    Renderer renderer(run.scene, test::glContext().info());
    renderer.render();
    run.image = renderer.readColor();
    run.aovs = renderer.readAovs();
    return run;
  }
  std::vector<Expected> closedForm(const Run& run, int assumed) const {
    const glm::vec3 colors[3] = {squareColor(0), squareColor(1), squareColor(2)};
    return ::closedForm(GetParam(), run.aovs, run.scene, colors, assumed);
  }
};

// All layers peeled: the image is the closed form within 8-bit rounding of the result and of
// the squares' colours (2/255, plus compare()'s twentieth of a pixel), at every pixel away from
// a square's border and where a fate may round either way; and a good part of it is really
// translucent.
TEST_P(TranslucentStack, EveryPixelIsTheClosedForm) {
  const Run run = render(8);
  const auto expected = closedForm(run, 8);
  int partly = 0;
  for (const Expected& e : expected) partly += e.smooth && e.translucent;
  const Comparison c = compare(run.image, expected);
  EXPECT_GT(c.checked, kSize * kSize / 2);
  EXPECT_LE(c.maxError, 1.0) << c.over << " of " << c.checked << " pixels off; mean "
                             << c.meanError * 255.0 << "/255; worst " << c.worst;
  EXPECT_GT(partly, 1000);
}

// One layer of a depth complexity up to three: the image follows the closed form cut short,
// and differs from the exact one, which measures what the layer budget costs.
TEST_P(TranslucentStack, ALayerBudgetKeepsTheNearestLayersOnly) {
  const Run run = render(1);
  const Comparison truncated = compare(run.image, closedForm(run, 1));
  const Comparison exact = compare(run.image, closedForm(run, 8));
  EXPECT_LE(truncated.maxError, 1.0)
      << truncated.over << " of " << truncated.checked << " pixels off; worst " << truncated.worst;
  EXPECT_GT(exact.over, 500) << "one layer should differ from all layers";
  std::cout << "one layer against exact peeling: mean error " << exact.meanError * 255.0
            << "/255, max " << exact.maxAbsolute * 255.0 << "/255, " << exact.over << " of "
            << exact.checked << " pixels off\n";
}

INSTANTIATE_TEST_SUITE_P(Applications, TranslucentStack,
                         ::testing::Values(ContextualCutawayOptions::Application::Translucency,
                                           ContextualCutawayOptions::Application::EdgeHighlights),
                         [](const auto& info) {
                           return info.param == ContextualCutawayOptions::Application::Translucency
                                      ? std::string("Translucency")
                                      : std::string("EdgeHighlights");
                         });

// Burns11 eqs. 2.1–2.2, §2.3 and §5.2.4 as the mirror states them.
TEST(ReducedOpacity, Equations21And22) {
  using A = ContextualCutawayOptions::Application;
  EXPECT_FLOAT_EQ(reducedOpacity(A::Translucency, 0.3f, 0.7f, 2.0f).x, 0.7f);
  EXPECT_FLOAT_EQ(reducedOpacity(A::EdgeHighlights, 0.6f, 1.0f, 2.0f).x,
                  0.4f);  // facing: as eq. 2.1
  EXPECT_FLOAT_EQ(reducedOpacity(A::EdgeHighlights, 0.6f, 0.0f, 2.0f).x, 1.0f);  // edge-on: opaque
  EXPECT_FLOAT_EQ(reducedOpacity(A::EdgeHighlights, 0.6f, 0.5f, 3.0f).x,
                  1.0f - 0.6f * (1.0f - 0.125f));
  // Never below plain translucency's opacity for the same R (§2.2's remark); lines as their
  // surface.
  for (float nDotV : {0.0f, 0.3f, 0.9f, 1.0f}) {
    const glm::vec2 edge = reducedOpacity(A::EdgeHighlights, 0.8f, nDotV, 4.0f);
    EXPECT_GE(edge.x, reducedOpacity(A::Translucency, 0.8f, nDotV, 4.0f).x);
    EXPECT_EQ(edge.y, edge.x);
  }
  EXPECT_EQ(reducedOpacity(A::Cut, 0.49f, 0.5f, 2.0f), glm::vec2(1.0f));
  EXPECT_EQ(reducedOpacity(A::Cut, 0.5f, 0.5f, 2.0f), glm::vec2(0.0f));
  // §2.3: surfaces suppressed wherever R > 0, their lines fading with R.
  EXPECT_EQ(reducedOpacity(A::Lines, 0.0f, 0.5f, 2.0f), glm::vec2(1.0f, 1.0f));
  EXPECT_EQ(reducedOpacity(A::Lines, 0.3f, 0.5f, 2.0f), glm::vec2(0.0f, 0.7f));
  EXPECT_EQ(reducedOpacity(A::Lines, 1.0f, 0.5f, 2.0f), glm::vec2(0.0f, 0.0f));
}

namespace {

// A 3 × 3 square facing an orthographic camera 10 units away, in front of an invisible box that
// fills the view 16 units away, cut by a contextual structure without a transition region
// whose overlay reaches 10 units in front of C₁: Ω = (16 − 10) / 10 = 0.6 on the whole square,
// and R = Ω.
Scene squareScene() {
  return parseScene(R"({
      "resolution": [96, 96], "samples": 4,
      "style": {"name": "blinn-phong", "lines": {"width": 2}},
      "camera": {"projection": "orthographic", "eye": [0, 0, 10], "target": [0, 0, 0],
                 "height": 6, "near": 1, "far": 30},
      "objects": [{"name": "square", "file": "plane.obj", "color": [0.5, 0.5, 0.5],
                   "transform": {"scale": 0.15}}],
      "proxies": [{"name": "roi", "box": {"min": [-20, -20, -6], "max": [20, 20, -4]},
                   "role": "interest"}],
      "cutters": {"adaptive": {"angle": 30, "outlines": false,
          "contextual": {"transitionAngle": 30, "overlay": 10, "reduction": "occlusion",
                         "apply": "lines"}}}})",
                    "line-square.json", kData + "/render");
}

}  // namespace

// Burns11 §2.3 as §7.2 applies it: in the overlay the square's surface is gone and its
// silhouette stays, faded to 1 − R: every pixel is the white background under the uncut
// square's line coverage times 0.4 (within 8-bit rounding), so the lines are the same lines.
TEST(TranslucentLines, SurfacesGoAndTheirLinesFadeByR) {
  Scene plain = squareScene();
  plain.cutters.clear();
  Renderer uncut(plain, test::glContext().info());
  uncut.render();
  const auto aovs = uncut.readAovs();
  const FloatImage& coverage = test::aov(aovs, "lines");
  const Scene scene = squareScene();
  Renderer renderer(scene, test::glContext().info());
  renderer.render();
  const Rgba8Image image = renderer.readColor();
  int linePixels = 0;
  for (int y = 0; y < scene.height; ++y)
    for (int x = 0; x < scene.width; ++x) {
      const float line = 0.4f * *coverage.at(x, y);
      linePixels += line > 0.2f;
      const float expected = 255.0f * (1.0f - line);  // black lines over white
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(float(image.at(x, y)[c]), expected, 1.5f)
            << "pixel " << x << "," << y << " channel " << c << ", uncut coverage "
            << *coverage.at(x, y);
    }
  EXPECT_GT(linePixels, 4 * 40);  // the square's outline, 2 pixels wide
}

// The documented fallback: a contextual structure without a region of interest has no
// cutaway surface in front of anything (Ω = 0 everywhere), so nothing is reduced and the
// image is the uncut one.
TEST(TranslucentLines, WithoutARegionOfInterestNothingIsReduced) {
  Scene scene = squareScene();
  scene.objects.erase(std::remove_if(scene.objects.begin(), scene.objects.end(),
                                     [](const SceneObject& o) { return o.role == Role::Interest; }),
                      scene.objects.end());
  ASSERT_EQ(scene.objects.size(), 1u);
  Scene plain = scene;
  plain.cutters.clear();
  Renderer uncut(plain, test::glContext().info()), cut(scene, test::glContext().info());
  uncut.render();
  cut.render();
  EXPECT_EQ(cut.readColor().pixels, uncut.readColor().pixels);
}
