// Blinn-Phong shading (blinn_phong.glsl): its options and uniform block.
#include "cutaway/styles/blinn_phong.hpp"

#include "frame/uniform_block.hpp"
#include "styles/style.hpp"

namespace cutaway {

const OptionsSchema& blinnPhongSchema() {
  using O = BlinnPhongStyle;
  static const OptionsSchema schema =
      OptionsBuilder<O>()
          .number("ambient", &O::ambient, 0, 1,
                  {.doc = "Ambient term as a fraction of the object colour.", .live = true})
          .build();
  return schema;
}

namespace {

class BlinnPhongShading : public ShadingStyle {
 public:
  explicit BlinnPhongShading(FrameSetup& setup) : setup_(setup), block_(setup.bindings, "STYLE") {}
  void beginFrame(const FrameState&) override {
    block_.update({glm::vec4(setup_.scene.style.get<BlinnPhongStyle>().ambient, 0, 0, 0)});
  }
  void bindForGeometry() const override { block_.bind(); }

 private:
  struct Block {  // std140 mirror of blinn_phong.glsl's BlinnPhongUniforms
    glm::vec4 params;
  };
  FrameSetup& setup_;
  UniformBlock<Block> block_;
};

}  // namespace

StyleType blinnPhongStyleType() {
  return {.name = "blinn-phong",
          .key = BlinnPhongStyle::kKey,
          .title = "Blinn-Phong",
          .glsl = "styles/blinn_phong/blinn_phong.glsl",
          .schema = &blinnPhongSchema(),
          .create = [](FrameSetup& setup) -> std::unique_ptr<ShadingStyle> {
            return std::make_unique<BlinnPhongShading>(setup);
          }};
}

}  // namespace cutaway
