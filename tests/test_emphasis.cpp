// Emphasis by importance (Burns11 §3.3.1): the folded C++ mirror against eqs. 3.1–3.4 as the
// paper writes them, and the GPU's colours on a flat-shaded test scene against those
// equations applied to the same scene's colours without emphasis, pixel by pixel.
#include <gtest/gtest.h>

#include <cmath>

#include "cutaway/render/renderer.hpp"
#include "cutaway/styles/emphasis.hpp"
#include "render_aovs.hpp"

using namespace cutaway;

namespace {

const std::string kData = CUTAWAY_TEST_DATA;

// Eqs. 3.1–3.4 term by term: shading suppressed, then the colour desaturated.
glm::vec3 paperEmphasis(float ec, float es, glm::vec3 c, glm::vec3 shaded, float importance) {
  const glm::vec3 partial = c * es + shaded * (1.0f - es);                           // eq. 3.3
  const glm::vec3 suppressed = shaded * importance + partial * (1.0f - importance);  // eq. 3.4
  const float ci = 0.2126f * suppressed.r + 0.7152f * suppressed.g + 0.0722f * suppressed.b;
  const glm::vec3 desaturated = glm::vec3(ci) * ec + suppressed * (1.0f - ec);  // eq. 3.1
  return suppressed * importance + desaturated * (1.0f - importance);           // eq. 3.2
}

}  // namespace

TEST(Emphasis, MirrorEqualsEquations31To34) {
  const glm::vec3 base(0.9f, 0.2f, 0.1f), shaded(0.5f, 0.7f, 0.05f);
  for (float ec : {0.0f, 0.3f, 1.0f})
    for (float es : {0.0f, 0.6f, 1.0f})
      for (float importance : {0.0f, 0.25f, 0.5f, 1.0f}) {
        const glm::vec3 got = emphasize({.color = ec, .shading = es}, base, shaded, importance);
        const glm::vec3 want = paperEmphasis(ec, es, base, shaded, importance);
        for (int k = 0; k < 3; ++k)
          EXPECT_NEAR(got[k], want[k], 1e-6f)
              << "E_c " << ec << " E_s " << es << " I " << importance << " channel " << k;
      }
}

// The paper's ends: E = 0 or I = 1 change nothing; E_c = 1 greys an object of importance 0
// fully (every channel its intensity); E_s = 1 gives it its flat base colour.
TEST(Emphasis, EndsOfTheStrengthsAndImportance) {
  const glm::vec3 base(0.9f, 0.2f, 0.1f), shaded(0.5f, 0.7f, 0.05f);
  EXPECT_EQ(emphasize({}, base, shaded, 0.0f), shaded);
  EXPECT_EQ(emphasize({.color = 1, .shading = 1}, base, shaded, 1.0f), shaded);
  const glm::vec3 grey = emphasize({.color = 1}, base, shaded, 0.0f);
  EXPECT_NEAR(grey.r, intensity(shaded), 1e-6f);
  EXPECT_NEAR(grey.g, grey.r, 1e-6f);
  EXPECT_NEAR(grey.b, grey.r, 1e-6f);
  EXPECT_EQ(emphasize({.shading = 1}, base, shaded, 0.0f), base);
  EXPECT_EQ(emphasize({.linesOnlyBelow = 0.5f, .paper = glm::vec3(1, 1, 0.9f)}, base, shaded, 0.4f),
            glm::vec3(1, 1, 0.9f));
  // Hybrid importance (§3.2): an object of interest is of high binary importance.
  EXPECT_EQ(emphasisImportance(true, 0.2f), 1.0f);
  EXPECT_EQ(emphasisImportance(false, 0.2f), 0.2f);
}

namespace {

// Three squares facing the camera under a near point light (so the shading varies across
// each; dim enough that no channel saturates), Blinn-Phong with a white highlight, no lines,
// one sample: importance 0, 0.4, and an object of interest whose own importance (0.1) the
// hybrid model overrides.
Scene emphasisScene(const std::string& emphasis) {
  return parseScene(R"({
      "resolution": [120, 50], "samples": 1,
      "style": {"name": "blinn-phong", "lines": false, "emphasis": )" +
                        emphasis + R"(},
      "lights": [{"type": "point", "position": [0, 0, 1.5], "space": "world", "intensity": 0.6}],
      "camera": {"eye": [0, 0, 8], "target": [0, 0, 0], "fov": 30, "near": 1, "far": 20},
      "objects": [
        {"name": "low", "file": "plane.obj", "color": [0.9, 0.25, 0.1], "importance": 0,
         "transform": {"translate": [-2.4, 0, 0], "scale": 0.1}},
        {"name": "mid", "file": "plane.obj", "color": [0.1, 0.6, 0.9], "importance": 0.4,
         "transform": {"translate": [0, 0, 0], "scale": 0.1}},
        {"name": "interest", "file": "plane.obj", "color": [0.2, 0.8, 0.3], "importance": 0.1,
         "role": "interest", "transform": {"translate": [2.4, 0, 0], "scale": 0.1}}]})",
                    "emphasis.json", kData + "/render");
}

struct Rendered {
  Rgba8Image color;
  FloatImage objectId;
};

Rendered renderFrame(const Scene& scene) {
  Renderer renderer(scene, test::glContext().info());
  renderer.render();
  const auto aovs = renderer.readAovs();
  return {renderer.readColor(), test::aov(aovs, "objectId")};
}

glm::vec3 rgb(const Rgba8Image& image, int x, int y) {
  const auto* p = image.at(x, y);
  return glm::vec3(p[0], p[1], p[2]) / 255.0f;
}

}  // namespace

// Each pixel of each square: the emphasised colour equals eqs. 3.1–3.4 applied to the same
// pixel without emphasis (c_shaded) and the square's colour (c), within one 8-bit step plus
// the rounding of c_shaded (the equations are linear with weights ≤ 1). The low square must
// really change (so that the test can fail) and the object of interest must not.
TEST(EmphasisRender, ColoursFollowEquations31To34PixelByPixel) {
  const float ec = 0.8f, es = 0.6f;
  const Scene plain = emphasisScene("{}");
  const Scene emphasised = emphasisScene(R"({"color": 0.8, "shading": 0.6})");
  const Rendered a = renderFrame(plain), b = renderFrame(emphasised);
  const float importance[3] = {0.0f, 0.4f, 1.0f};
  int checked[3] = {0, 0, 0};
  float largestChange[3] = {0, 0, 0};
  for (int y = 1; y + 1 < plain.height; ++y)
    for (int x = 1; x + 1 < plain.width; ++x) {
      const float id = a.objectId.at(x, y)[0];
      if (id < 0) continue;
      // Inside a square: its four neighbours show it too.
      if (a.objectId.at(x - 1, y)[0] != id || a.objectId.at(x + 1, y)[0] != id ||
          a.objectId.at(x, y - 1)[0] != id || a.objectId.at(x, y + 1)[0] != id)
        continue;
      const int k = int(id);
      const glm::vec3 shaded = rgb(a.color, x, y), got = rgb(b.color, x, y);
      const glm::vec3 want = paperEmphasis(ec, es, plain.objects[std::size_t(k)].material.color,
                                           shaded, importance[k]);
      for (int c = 0; c < 3; ++c) {
        ASSERT_NEAR(got[c], want[c], 1.5f / 255.0f)
            << "pixel " << x << "," << y << " object " << k << " channel " << c;
        largestChange[k] = std::max(largestChange[k], std::abs(got[c] - shaded[c]));
      }
      ++checked[k];
    }
  for (int k = 0; k < 3; ++k) EXPECT_GT(checked[k], 300) << "object " << k;
  EXPECT_GT(largestChange[0], 0.2f);
  EXPECT_GT(largestChange[1], 0.05f);
  EXPECT_EQ(largestChange[2], 0.0f);
}

// §3.3.1.3: below the threshold an object is its paper colour (lines are off here), above it
// unchanged.
TEST(EmphasisRender, LinesOnlyBelowTheThresholdShowsThePaper) {
  const Rendered a = renderFrame(emphasisScene("{}"));
  const Rendered b =
      renderFrame(emphasisScene(R"({"linesOnlyBelow": 0.5, "paper": [1, 0.95, 0.8]})"));
  int paper = 0, unchanged = 0;
  for (int y = 0; y < a.color.height; ++y)
    for (int x = 0; x < a.color.width; ++x) {
      const float id = a.objectId.at(x, y)[0];
      if (id < 0) continue;
      const glm::vec3 got = rgb(b.color, x, y);
      if (id < 2) {
        ASSERT_EQ(glm::ivec3(glm::round(got * 255.0f)), glm::ivec3(255, 242, 204))
            << "pixel " << x << "," << y;
        ++paper;
      } else {
        ASSERT_EQ(got, rgb(a.color, x, y)) << "pixel " << x << "," << y;
        ++unchanged;
      }
    }
  EXPECT_GT(paper, 600);
  EXPECT_GT(unchanged, 300);
}
