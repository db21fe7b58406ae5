// Hatching with tonal art maps (hatching.glsl, Praun01): its options, texture and uniform block.
#include "cutaway/styles/hatching.hpp"

#include <algorithm>

#include "frame/uniform_block.hpp"
#include "styles/hatching/tonal_art_map.hpp"
#include "styles/style.hpp"

namespace cutaway {

const OptionsSchema& hatchingSchema() {
  using O = HatchingStyle;
  static const OptionsSchema schema =
      OptionsBuilder<O>()
          .number("tones", &O::tones, 2, 12,
                  {.doc = "Tones of the tonal art map, lightest to darkest (Praun01 §3)."})
          .color("paper", &O::paper, {.doc = "Colour between the strokes.", .live = true})
          .color("ink", &O::ink, {.doc = "Colour of the strokes.", .live = true})
          .number("tint", &O::tint, 0, 1,
                  {.doc = "How much the object colour tints the paper.", .live = true})
          .number("scale", &O::scale, 1e-3, 10,
                  {.doc = "Hatch tile size as a fraction of the scene's bounding radius.", .live = true})
          .choice("lightness", &O::lightness,
                  {{"lambert", O::Lightness::Lambert}, {"gooch", O::Lightness::Gooch}},
                  {.doc = "The surface's lightness from the key light: Lambert max(n·l, 0), or "
                          "Gooch's (1 + n·l)/2.",
                   .live = true})
          .number("seed", &O::seed, 0, 1 << 30, {.doc = "Stroke placement."})
          .build();
  return schema;
}

namespace {

class HatchingShading : public ShadingStyle {
 public:
  explicit HatchingShading(FrameSetup& setup)
      : setup_(setup),
        block_(setup.bindings, "STYLE"),
        mapUnit_(setup.bindings.textureUnit("TONAL_ART_MAP")),
        tones_(setup.scene.style.get<HatchingStyle>().tones),
        map_(createTonalArtMapTexture(generateTonalArtMap(
            {.tones = tones_, .seed = setup.scene.style.get<HatchingStyle>().seed}))) {}
  void beginFrame(const FrameState&) override {
    const HatchingStyle& h = setup_.scene.style.get<HatchingStyle>();
    const float sceneRadius = std::max(setup_.sceneBounds.radius(), 1e-6f);
    block_.update({glm::vec4(h.paper, h.tint), glm::vec4(h.ink, float(tones_)),
                   glm::vec4(1.0f / (h.scale * sceneRadius),
                             h.lightness == HatchingStyle::Lightness::Gooch ? 1.0f : 0.0f, 0, 0)});
  }
  void bindForGeometry() const override {
    block_.bind();
    glBindTextureUnit(mapUnit_, map_.id());
  }

 private:
  struct Block {  // std140 mirror of hatching.glsl's HatchingUniforms
    glm::vec4 paper, ink, params;
  };
  FrameSetup& setup_;
  UniformBlock<Block> block_;
  GLuint mapUnit_;
  int tones_;  // the texture's, until a new renderer
  gl::Texture map_;
};

}  // namespace

StyleType hatchingStyleType() {
  return {.name = "hatching",
          .key = HatchingStyle::kKey,
          .title = "Hatching (Praun01)",
          .glsl = "styles/hatching/hatching.glsl",
          .schema = &hatchingSchema(),
          .create = [](FrameSetup& setup) -> std::unique_ptr<ShadingStyle> {
            return std::make_unique<HatchingShading>(setup);
          }};
}

}  // namespace cutaway
