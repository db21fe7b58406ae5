// The cutout cutter's options as the scene file, the viewer and the CLI name them.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/json_reader.hpp"
#include "cutaway/cutters/cutout.hpp"

namespace cutaway {

namespace {

using O = CutoutOptions;
using J = CutoutJitter;
using Type = OptionSpec::Type;

OptionsSchema jitterSchema() {
  return OptionsBuilder<J>()
      .choice("pattern", &J::pattern,
              {{"none", J::Pattern::None},
               {"sawtooth", J::Pattern::Sawtooth},
               {"noise", J::Pattern::Noise},
               {"image", J::Pattern::Image}},
              {.label = "jitter",
               .doc = "Rough cut boundaries (rule 4, §4.5): a sawtooth, fractal noise or a PNG "
                      "displaces the signed distance.",
               .required = true})
      .number("amplitude", &J::amplitude, 0, 1,
              {.label = "jitter amplitude",
               .doc = "Displacement, as a fraction of the main axis' extent.",
               .live = true,
               .sliderMax = 0.2})
      .number("frequency", &J::frequency, 1e-3, 1e4,
              {.label = "jitter frequency",
               .doc = "Pattern repeats per extent along the main axis.",
               .live = true,
               .sliderMax = 60})
      .number("octaves", &J::octaves, 1, 8,
              {.label = "jitter octaves", .doc = "Octaves of the noise pattern.", .live = true})
      // "image": a PNG's grey levels, relative to the scene file.
      .readHook([](const json_reader::Context& ctx, json_reader::ObjectReader& r, J& j) {
        const auto* x = r.take("image");
        if (!x) return;
        if (!x->is_string())
          ctx.fail(r.at("image"), "expected a file name, got " + json_reader::typeName(*x));
        j.image = ctx.baseDir / json_reader::string(ctx, *x, r.at("image"));
        if (!std::filesystem::is_regular_file(j.image))
          ctx.fail(r.at("image"), "no such image file: " + j.image.string());
        try {
          j.imageData = readPngGray(j.image);
        } catch (const Error& e) {
          ctx.fail(r.at("image"), e.reason() + " (" + j.image.string() + ")");
        }
      })
      .check([](const json_reader::Context& ctx, json_reader::ObjectReader& r, J& j) {
        if (j.pattern == J::Pattern::Image && j.image.empty())
          ctx.fail(r.pointer(), "pattern \"image\" needs an \"image\" file (a PNG)");
      })
      .writeHook([](const J& j, nlohmann::ordered_json& out) {
        if (j.pattern == J::Pattern::Image && !j.image.empty())
          out["image"] = std::filesystem::absolute(j.image).string();
      })
      .build();
}

}  // namespace

const OptionsSchema& cutoutSchema() {
  static const OptionsSchema schema =
      OptionsBuilder<O>()
          // "axialRange": [from, to], parts of the main axis' extent.
          .readHook([](const json_reader::Context& ctx, json_reader::ObjectReader& r, O& o) {
            const auto* v = r.take("axialRange");
            if (!v) return;
            if (!v->is_array() || v->size() != 2) ctx.fail(r.at("axialRange"), "expected [from, to]");
            const float from = float(json_reader::number(ctx, (*v)[0], r.at("axialRange") + "/0", 0, 1));
            const float to = float(json_reader::number(ctx, (*v)[1], r.at("axialRange") + "/1", 0, 1));
            if (to <= from) ctx.fail(r.at("axialRange"), "the range must not be empty (from < to)");
            o.axialRange = glm::vec2(from, to);
          })
          .choice("method", &O::method,
                  {{"texture", O::Method::Texture}, {"clipPlanes", O::Method::ClipPlanes}},
                  {.doc = "texture: per-fragment signed distances with jitter and walls (§4.5); "
                          "clipPlanes: hardware clip planes, one pass per plane (§4.3)."})
          .number("angle", &O::angle, 1, 180,
                  {.label = "wedge angle (°)",
                   .doc = "Relative angle between the two planes (rule 2; default 90°).",
                   .live = true})
          .derived(
              "facingCamera", Type::Bool, 0, 0,
              [](const O& o) -> OptionValue { return !o.rotation; },
              [](O& o, const OptionValue& v) {
                if (std::get<bool>(v))
                  o.rotation.reset();
                else if (!o.rotation)
                  o.rotation = 0.0f;
              },
              {.label = "faces the camera",
               .doc = "Turn the wedge about the main axis towards the viewer (rule 3), or hold "
                      "it at the rotation.",
               .live = true})
          .optional("rotation", &O::rotation, Type::Float, -360, 360, 0.0f,
                    {.label = "rotation (°)",
                     .doc = "The wedge's rotation about the main axis, from the second principal "
                            "axis; unset: it faces the camera.",
                     .live = true,
                     .sliderMax = 180})
          .applies([](const O& o) { return o.rotation.has_value(); })
          .group("jitter", &O::jitter, jitterSchema(), {.doc = "Diepstraten03 §4.5's jitter."})
          .optional("wallColor", &O::wallColor, Type::Color, 0, 1, kDefaultWallColor,
                    {.label = "wall colour",
                     .doc = "Colour of the cut walls of solid exteriors (rule 5).",
                     .live = true})
          .optional("insideColor", &O::insideColor, Type::Color, 0, 1, glm::vec3(0.4f),
                    {.label = "inside colour",
                     .doc = "Back faces of hollow exteriors; unset: the object's colour, darker.",
                     .live = true})
          .check([](const json_reader::Context& ctx, json_reader::ObjectReader& r, O& o) {
            if (o.method == O::Method::ClipPlanes && o.jitter.pattern != J::Pattern::None)
              ctx.fail(r.at("jitter"),
                       "the clip-plane method cannot jitter (Diepstraten03 §4.3); use "
                       "\"method\": \"texture\"");
          })
          .writeHook([](const O& o, nlohmann::ordered_json& out) {
            if (o.axialRange)
              out["axialRange"] = {json_reader::exact(o.axialRange->x), json_reader::exact(o.axialRange->y)};
          })
          .build();
  return schema;
}

}  // namespace cutaway
