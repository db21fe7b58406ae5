// Gooch cool-to-warm shading (gooch.glsl): its options and uniform block.
#include "cutaway/styles/gooch.hpp"

#include "frame/uniform_block.hpp"
#include "styles/style.hpp"

namespace cutaway {

const OptionsSchema& goochSchema() {
  using O = GoochStyle;
  static const OptionsSchema schema =
      OptionsBuilder<O>()
          .color("cool", &O::cool,
                 {.doc = "Cool tone k_blue, for surfaces turned away from the key light (Gooch98).",
                  .live = true})
          .color("warm", &O::warm,
                 {.doc = "Warm tone k_yellow, for surfaces turned towards the key light.", .live = true})
          .number("alpha", &O::alpha, 0, 1,
                  {.doc = "How much of the object colour enters the cool tone.", .live = true})
          .number("beta", &O::beta, 0, 1,
                  {.doc = "How much of the object colour enters the warm tone.", .live = true})
          .build();
  return schema;
}

namespace {

class GoochShading : public ShadingStyle {
 public:
  explicit GoochShading(FrameSetup& setup) : setup_(setup), block_(setup.bindings, "STYLE") {}
  void beginFrame(const FrameState&) override {
    const GoochStyle& g = setup_.scene.style.get<GoochStyle>();
    block_.update({glm::vec4(g.cool, g.alpha), glm::vec4(g.warm, g.beta)});
  }
  void bindForGeometry() const override { block_.bind(); }

 private:
  struct Block {  // std140 mirror of gooch.glsl's GoochUniforms
    glm::vec4 cool, warm;
  };
  FrameSetup& setup_;
  UniformBlock<Block> block_;
};

}  // namespace

StyleType goochStyleType() {
  return {.name = "gooch",
          .key = GoochStyle::kKey,
          .title = "Gooch (cool to warm)",
          .glsl = "styles/gooch/gooch.glsl",
          .schema = &goochSchema(),
          .create = [](FrameSetup& setup) -> std::unique_ptr<ShadingStyle> {
            return std::make_unique<GoochShading>(setup);
          }};
}

}  // namespace cutaway
