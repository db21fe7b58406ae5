// The contextual cutaway structure (Burns11 §4.1.3, §5.2.3) and occlusion reduction by
// importance (eqs. 7.1–7.3): the C++ functions against the paper's statements, and the GPU's Ω
// and R per pixel against those functions evaluated on the frame's dumped C₁, C₂ and depths.
#include <gtest/gtest.h>

#include <cmath>

#include "cutaway/cutters/adaptive.hpp"
#include "cutaway/scene/scene.hpp"
#include "render_aovs.hpp"

using namespace cutaway;

namespace {

// Eq. 5.6 as printed, p_z measured towards the viewer (−z), C₂ < C₁ < C₁ + d in that measure.
float eq56(float z1, float z2, float d, float z) {
  return (ramp(-z2, -z1, -z) + ramp(-z1, -z1 + d, -z)) / 2.0f;
}

}  // namespace

TEST(ContextualStructure, OcclusionIsEq56WithBothRegionsAndHitsItsBoundaries) {
  const ContextualRay r{.z1 = 10.0f, .z2 = 14.0f, .d = 2.0f, .t = transitionOverlayOcclusion(true, true)};
  EXPECT_EQ(r.t, 0.5f);
  for (float z = 5.0f; z <= 16.0f; z += 0.125f)
    EXPECT_FLOAT_EQ(contextualOcclusion(r, z), eq56(r.z1, r.z2, r.d, z)) << z;
  EXPECT_EQ(contextualOcclusion(r, 14.5f), 0.0f);   // base
  EXPECT_EQ(contextualOcclusion(r, 14.0f), 0.0f);   // at C₂
  EXPECT_FLOAT_EQ(contextualOcclusion(r, 12.0f), 0.25f);  // half-way through the transition
  EXPECT_FLOAT_EQ(contextualOcclusion(r, 10.0f), 0.5f);   // at C₁: t
  EXPECT_FLOAT_EQ(contextualOcclusion(r, 9.0f), 0.75f);   // half-way through the overlay
  EXPECT_EQ(contextualOcclusion(r, 8.0f), 1.0f);    // at C₁ − d: clear
}

// §4.1.3.3: t = 0 without a transition region, 1 without an overlay; with neither, eq. 5.3.
TEST(ContextualStructure, CollapsedRegionsMoveT) {
  EXPECT_EQ(transitionOverlayOcclusion(false, true), 0.0f);
  EXPECT_EQ(transitionOverlayOcclusion(true, false), 1.0f);
  const ContextualRay noTransition{10, 10, 2, 0.0f}, noOverlay{10, 14, 0, 1.0f}, simple{10, 10, 0, 0.0f};
  EXPECT_FLOAT_EQ(contextualOcclusion(noTransition, 9.0f), 0.5f);
  EXPECT_EQ(contextualOcclusion(noTransition, 10.5f), 0.0f);
  EXPECT_FLOAT_EQ(contextualOcclusion(noOverlay, 12.0f), 0.5f);
  EXPECT_EQ(contextualOcclusion(noOverlay, 9.99f), 1.0f);
  EXPECT_EQ(contextualOcclusion(simple, 10.01f), 0.0f);
  EXPECT_EQ(contextualOcclusion(simple, 9.99f), 1.0f);
}

// occlusionDistance inverts Ω on every ray shape.
TEST(ContextualStructure, OcclusionDistanceInvertsOcclusion) {
  for (const ContextualRay& r : {ContextualRay{10, 14, 2, 0.5f}, ContextualRay{10, 10, 2, 0.0f},
                                 ContextualRay{10, 14, 0, 1.0f}})
    for (float omega = 0.05f; omega <= 1.0f; omega += 0.05f)
      EXPECT_NEAR(contextualOcclusion(r, occlusionDistance(r, omega)), omega, 1e-5f) << r.t << " " << omega;
}

// §5.2.3's rules for R(I, Ω) and §7.1.2's ends of eqs. 7.1–7.3.
TEST(OcclusionReduction, FollowsEqs71To73AndTheirRules) {
  for (float omega = 0.0f; omega <= 1.0f; omega += 0.01f) {
    EXPECT_EQ(occlusionReduction(omega, 1.0f), 0.0f) << omega;                 // never reduced
    EXPECT_EQ(occlusionReduction(omega, 0.0f), omega > 0.0f ? 1.0f : 0.0f);    // all but the base
  }
  EXPECT_FLOAT_EQ(occlusionReduction(0.55f, 0.7f), 0.5f);  // τ₀ = 0.4, τ₁ = 0.7
  EXPECT_FLOAT_EQ(occlusionReduction(0.2f, 0.4f), 0.5f);   // τ₀ = 0, τ₁ = 0.4
  for (float i = 0.0f; i <= 1.0f; i += 0.05f)
    for (float omega = 0.0f; omega <= 1.0f; omega += 0.05f) {
      EXPECT_EQ(occlusionReduction(0.0f, i), 0.0f);  // no reduction in the base region
      EXPECT_LE(occlusionReduction(omega, i), occlusionReduction(omega + 0.05f, i));  // up with Ω
      EXPECT_GE(occlusionReduction(omega, i), occlusionReduction(omega, i + 0.05f));  // down with I
    }
  for (float i = 0.05f; i < 1.0f; i += 0.05f)
    EXPECT_NEAR(occlusionReduction(trimOcclusion(i), i), 0.5f, 1e-5f) << i;
  EXPECT_GT(trimOcclusion(1.0f), 1.0f);
}

namespace {

// The engine with graded importance around its pistons, cut by the contextual structure at
// a square size equal to the cutaway buffer's, so that a pixel centre is a texel centre.
Scene contextualEngine(ContextualCutawayOptions::Reduction reduction) {
  Scene scene = loadScene(std::string(CUTAWAY_SOURCE_DIR) + "/examples/engine-contextual.json");
  scene.width = scene.height = 256;
  scene.samples = 1;
  auto& adaptive = *scene.cutters.find<AdaptiveCutawayOptions>();
  adaptive.bufferSize = 256;
  adaptive.contextual->reduction = reduction;
  return scene;
}

// View distance of window depth `c` (perspective: independent of the pixel).
float viewDistance(const glm::mat4& inverseProjection, float c) {
  const glm::vec4 h = inverseProjection * glm::vec4(0.0f, 0.0f, 2.0f * c - 1.0f, 1.0f);
  return -h.z / h.w;
}

}  // namespace

class ContextualPixels : public ::testing::TestWithParam<ContextualCutawayOptions::Reduction> {};

TEST_P(ContextualPixels, OmegaAndRAreTheEquationsOnTheDumpedBuffers) {
  test::glContext();
  const Scene scene = contextualEngine(GetParam());
  const auto aovs = test::renderAovs(scene);
  const FloatImage &omegaGpu = test::aov(aovs, "occlusion"), &rGpu = test::aov(aovs, "reduction"),
                   &c1 = test::aov(aovs, "cutawayDepth"), &c2 = test::aov(aovs, "cutawayDepthC2"),
                   &z = test::aov(aovs, "viewDepth"), &cut = test::aov(aovs, "cutMask"),
                   &importance = test::aov(aovs, "importance");
  const ContextualCutawayOptions& c = *scene.cutters.find<AdaptiveCutawayOptions>()->contextual;
  ASSERT_TRUE(c.overlay.has_value());
  const glm::mat4 inverse = glm::inverse(scene.resolvedCamera().projectionMatrix(1.0f));
  const bool byOcclusion = GetParam() == ContextualCutawayOptions::Reduction::Occlusion;
  int checked = 0, transition = 0, overlay = 0;
  for (int y = 0; y < scene.height; ++y)
    for (int x = 0; x < scene.width; ++x) {
      const float omega = *omegaGpu.at(x, y);
      if (std::isnan(omega) || *cut.at(x, y) > 0.0f) continue;  // not cut, or a cut surface
      const float z1 = viewDistance(inverse, *c1.at(x, y));
      const ContextualRay ray{z1, std::max(viewDistance(inverse, *c2.at(x, y)), z1), *c.overlay, 0.5f};
      const float expected = contextualOcclusion(ray, *z.at(x, y));
      ASSERT_NEAR(omega, expected, 2e-3f) << x << "," << y;
      const float r = byOcclusion ? omega : occlusionReduction(omega, *importance.at(x, y));
      ASSERT_NEAR(*rGpu.at(x, y), r, 1e-5f) << x << "," << y;
      ASSERT_LT(*rGpu.at(x, y), 0.5f) << x << "," << y << ": R ≥ ½ is removed";
      ++checked;
      transition += omega > 0.01f && omega < 0.49f;
      overlay += omega > 0.51f;
    }
  EXPECT_GT(checked, 5000);
  EXPECT_GT(transition, 100) << "the transition region shows";
  if (!byOcclusion) EXPECT_GT(overlay, 20) << "important material shows in the overlay";
}

INSTANTIATE_TEST_SUITE_P(Reductions, ContextualPixels,
                         ::testing::Values(ContextualCutawayOptions::Reduction::Importance,
                                           ContextualCutawayOptions::Reduction::Occlusion),
                         [](const auto& info) {
                           return info.param == ContextualCutawayOptions::Reduction::Importance
                                      ? std::string("Importance")
                                      : std::string("Occlusion");
                         });

// With importance, each object is trimmed at its own surface: objects of lower importance
// lose more (Burns11 Fig. 4.4).
TEST(ContextualCutaway, LessImportantObjectsAreCutMore) {
  test::glContext();
  Scene scene = contextualEngine(ContextualCutawayOptions::Reduction::Importance);
  const auto count = [&](float importance) {
    for (SceneObject& o : scene.objects)
      if (o.role != Role::Interest) o.importance = importance;
    const auto aovs = test::renderAovs(scene);
    const FloatImage& id = test::aov(aovs, "objectId");
    int interest = 0;
    for (const float k : id.data)
      interest += k >= 0 && scene.objects[std::size_t(k)].role == Role::Interest;
    return interest;
  };
  const int low = count(0.1f), middle = count(0.5f), high = count(0.9f), top = count(1.0f);
  EXPECT_GT(low, middle);
  EXPECT_GT(middle, high);
  EXPECT_GT(high, top);
}
