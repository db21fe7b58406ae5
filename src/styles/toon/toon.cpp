// Toon shading (toon.glsl, Lake00): its options, ramp texture and uniform block.
#include "cutaway/styles/toon.hpp"

#include <nlohmann/json.hpp>

#include "core/json_reader.hpp"
#include "frame/uniform_block.hpp"
#include "styles/style.hpp"
#include "styles/toon/toon_ramp.hpp"

namespace cutaway {

const OptionsSchema& toonSchema() {
  using O = ToonStyle;
  using namespace json_reader;
  static const OptionsSchema schema =
      OptionsBuilder<O>()
          // "ramp": tones dark to light, each a grey level or a colour multiplying the object
          // colour (a texture: a change rebuilds).
          .readHook([](const Context& ctx, ObjectReader& r, O& t) {
            const json* v = r.take("ramp");
            if (!v) return;
            if (!v->is_array() || v->size() < 2 || v->size() > 16)
              ctx.fail(
                  r.at("ramp"),
                  "expected an array of 2 to 16 tones (numbers or colours), got " + sizeOrType(*v));
            t.ramp.clear();
            for (std::size_t i = 0; i < v->size(); ++i) {
              const std::string p = r.at("ramp") + "/" + std::to_string(i);
              const json& tone = (*v)[i];
              t.ramp.push_back(tone.is_array() ? color(ctx, tone, p)
                                               : glm::vec3(float(number(ctx, tone, p, 0, 1))));
            }
          })
          .value("highlight", &O::highlight,
                 {.doc = "A hard-edged highlight where the Blinn term passes the threshold (Lake00 "
                         "§3.1).",
                  .live = true})
          .number("highlightThreshold", &O::highlightThreshold, 0, 1,
                  {.label = "highlight threshold", .doc = "Blinn term (n·h)^shininess above which it shows.",
                   .live = true})
          .applies([](const O& o) { return o.highlight; })
          .color("highlightColor", &O::highlightColor,
                 {.label = "highlight colour", .doc = "Added, weighted by the object's specular.",
                  .live = true})
          .applies([](const O& o) { return o.highlight; })
          .writeHook([](const O& t, nlohmann::ordered_json& out) {
            nlohmann::ordered_json ramp = nlohmann::ordered_json::array();
            for (const glm::vec3& c : t.ramp) ramp.push_back({exact(c.x), exact(c.y), exact(c.z)});
            out["ramp"] = ramp;
          })
          .build();
  return schema;
}

namespace {

class ToonShading : public ShadingStyle {
 public:
  explicit ToonShading(FrameSetup& setup)
      : setup_(setup),
        block_(setup.bindings, "STYLE"),
        rampUnit_(setup.bindings.textureUnit("TOON_RAMP")),
        ramp_(createToonRampTexture(setup.scene.style.get<ToonStyle>())),
        rampSize_(setup.scene.style.get<ToonStyle>().ramp.size()) {}
  void beginFrame(const FrameState&) override {
    const ToonStyle& t = setup_.scene.style.get<ToonStyle>();
    block_.update({glm::vec4(float(rampSize_), t.highlightThreshold, t.highlight ? 1.0f : 0.0f, 0.0f),
                   glm::vec4(t.highlightColor, 1.0f)});
  }
  void bindForGeometry() const override {
    block_.bind();
    glBindTextureUnit(rampUnit_, ramp_.id());
  }

 private:
  struct Block {  // std140 mirror of toon.glsl's ToonUniforms
    glm::vec4 params, highlight;
  };
  FrameSetup& setup_;
  UniformBlock<Block> block_;
  GLuint rampUnit_;
  gl::Texture ramp_;
  std::size_t rampSize_;  // the texture's, until a new renderer
};

}  // namespace

StyleType toonStyleType() {
  return {.name = "toon",
          .key = ToonStyle::kKey,
          .title = "Toon (Lake00)",
          .glsl = "styles/toon/toon.glsl",
          .schema = &toonSchema(),
          .create = [](FrameSetup& setup) -> std::unique_ptr<ShadingStyle> {
            return std::make_unique<ToonShading>(setup);
          }};
}

}  // namespace cutaway
