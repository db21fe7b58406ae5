// The adaptive cutter's options as the scene file, the viewer and the CLI name them.
#include <nlohmann/json.hpp>

#include "core/json_reader.hpp"
#include "cutaway/cutters/adaptive.hpp"

namespace cutaway {

namespace {

using O = AdaptiveCutawayOptions;
using Type = OptionSpec::Type;

OptionsSchema ghostLinesSchema() {
  return OptionsBuilder<GhostLineOptions>()
      .number("distance", &GhostLineOptions::distance, 0, 1e30,
              {.label = "ghost distance",
               .doc = "World units in front of the cutaway surface over which ghost lines fade "
                      "out; 0: 5% of the scene radius.",
               .live = true})
      .number("opacity", &GhostLineOptions::opacity, 0, 1,
              {.label = "ghost opacity", .doc = "Opacity of the ghost lines over the image.",
               .live = true})
      .build();
}

OptionsSchema contextualSchema() {
  using C = ContextualCutawayOptions;
  return OptionsBuilder<C>()
      .number("transitionAngle", &C::transitionAngle, 0, 90,
              {.label = "transition angle θ₂ (°)",
               .doc = "Angle of C₂, the base–transition boundary (Burns11 §4.1.3.1); at least "
                      "the angle θ₁; equal: no transition region.",
               .live = true})
      .optional("overlay", &C::overlay, Type::Float, 0, 1e30, 0.0f,
                {.label = "overlay d",
                 .doc = "Thickness d of the overlay region in front of C₁, world units "
                        "(§4.1.3.2); 0: none; unset: 5% of the scene radius.",
                 .live = true})
      .choice("reduction", &C::reduction,
              {{"auto", C::Reduction::Auto},
               {"importance", C::Reduction::Importance},
               {"occlusion", C::Reduction::Occlusion}},
              {.doc = "R from Ω: by importance (Burns11 eqs. 7.1–7.3), R = Ω (§7.2), or auto: "
                      "by importance when the cut objects' importances differ (a volume's: its "
                      "transfer function's)."})
      .choice("apply", &C::apply,
              {{"cut", C::Application::Cut},
               {"translucency", C::Application::Translucency},
               {"edgeHighlights", C::Application::EdgeHighlights},
               {"lines", C::Application::Lines}},
              {.doc = "How R is applied: cut (fully or not at all, with cut surfaces: §5.2.4), "
                      "translucency (opacity 1 − R, eq. 2.1), edge highlights (eq. 2.2) or lines "
                      "(surfaces suppressed, feature lines of opacity 1 − R: §2.3), the last "
                      "three as translucent layers peeled in depth order."})
      .number("edgeExponent", &C::edgeExponent, 0.25, 16,
              {.label = "edge exponent k",
               .doc = "k of eq. 2.2: how fast opacity falls away from the edges (1–4 in the "
                      "paper).",
               .live = true})
      .number("layers", &C::layers, 1, 64,
              {.doc = "The most translucent layers peeled per pixel; peeling stops earlier at "
                      "the first empty layer, which makes the result exact.",
               .live = true})
      .build();
}

}  // namespace

const OptionsSchema& adaptiveCutawaySchema() {
  static const OptionsSchema schema =
      OptionsBuilder<O>()
          // "edgeCompression": true, false, or the width r of its region (which turns it on).
          .readHook([](const json_reader::Context& ctx, json_reader::ObjectReader& r, O& o) {
            if (const auto* v = r.take("edgeCompression")) {
              if (v->is_number())
                o.edgeRegion = float(json_reader::number(ctx, *v, r.at("edgeCompression"), 1e-3, 1)),
                o.edgeCompression = true;
              else
                o.edgeCompression = json_reader::boolean(ctx, *v, r.at("edgeCompression"));
            }
          })
          .number("angle", &O::angle, 0, 90,
                  {.label = "angle θ (°)",
                   .doc = "Angle between the cut's walls and the viewing ray (Burns08 §3); "
                          "objects may set their own (param cutawayAngle).",
                   .live = true})
          .number("bufferSize", &O::bufferSize, 16, 8192,
                  {.label = "buffer resolution",
                   .doc = "The cutaway buffer is n×n pixels whatever the view (Burns08 §6).",
                   .sliderMax = 2048})
          .value("perspectiveCompensation", &O::perspectiveCompensation,
                 {.label = "perspective compensation",
                  .doc = "Keep the walls at θ at any depth (Burns08 eq. 3, Burns11 eq. 5.7).",
                  .live = true})
          .value("edgeCompression", &O::edgeCompression,
                 {.label = "edge compression",
                  .doc = "Shrink θ to 0 near the view's border (Burns11 eq. 5.8); the file may "
                         "give the region's width r instead of true.",
                  .live = true})
          .number("edgeRegion", &O::edgeRegion, 1e-3, 1,
                  {.label = "edge region r",
                   .doc = "Width r of the border region of eq. 5.8, in [−1, 1] units.",
                   .live = true})
          .applies([](const O& o) { return o.edgeCompression; })
          .value("directionalConstraint", &O::directionalConstraint,
                 {.label = "directional constraint",
                  .doc = "Keep the cut off the floor (Burns08 §5.5, Burns11 eqs. 6.1–6.4); a "
                         "floorNormal turns it on unless given.",
                  .live = true})
          .direction("floorNormal", &O::floorNormal,
                     {.label = "floor normal",
                      .doc = "World-space normal of the floor the constraint protects.",
                      .live = true})
          .applies([](const O& o) { return o.directionalConstraint; })
          .alsoSets([](O& o) { o.directionalConstraint = true; })
          .choice(
              "jumpFlooding", &O::variant,
              {{"jfa", fields::JumpFloodingVariant::jfa},
               {"jfa+1", fields::JumpFloodingVariant::jfaPlus1},
               {"1+jfa", fields::JumpFloodingVariant::onePlusJfa},
               {"jfa+2", fields::JumpFloodingVariant::jfaPlus2}},
              {.label = "jump flooding", .doc = "Step sequence of jump flooding (Burns08 §5.1)."})
          .choice("compute", &O::compute,
                  {{"auto", O::Compute::Auto}, {"gpu", O::Compute::Gpu}, {"cpu", O::Compute::Cpu}},
                  {.doc = "Where jump flooding runs; auto: the CPU on llvmpipe."})
          .choice("cutSurfaces", &O::cutSurfaces,
                  {{"all", O::CutSurfaces::All},
                   {"unmarked", O::CutSurfaces::Unmarked},
                   {"watertight", O::CutSurfaces::Watertight},
                   {"none", O::CutSurfaces::None}},
                  {.label = "cut surfaces",
                   .doc = "Shade back faces behind the cut as solid cut surfaces (Burns08 §4.1): "
                          "on every mesh, on every mesh without telling an open one's inside "
                          "from its cut (faster), on watertight ones, or never.",
                   .live = true})
          .optional("cutSurfaceColor", &O::cutSurfaceColor, Type::Color, 0, 1, glm::vec3(0.6f),
                    {.label = "cut-surface colour",
                     .doc = "Colour of the cut surfaces; unset: the cut object's colour, darker.",
                     .live = true})
          .value("outlines", &O::outlines,
                 {.label = "cut outlines",
                  .doc = "Draw the boundary of the cut surfaces (Burns08 §4.2)."})
          .color("outlineColor", &O::outlineColor,
                 {.label = "outline colour", .doc = "Colour of the cut outlines.", .live = true})
          .applies([](const O& o) { return o.outlines; })
          .group("ghostLines", &O::ghostLines, ghostLinesSchema(),
                 {.label = "ghost lines",
                  .doc = "Faded lines of the removed material (Burns08 §4.3): true, false, or "
                         "{distance, opacity}."})
          .group("contextual", &O::contextual, contextualSchema(),
                 {.label = "contextual cutaway",
                  .doc = "The contextual cutaway structure (Burns11 §4.1.3): true, false, or "
                         "{transitionAngle, overlay, reduction}."})
          .check([](const json_reader::Context& ctx, json_reader::ObjectReader& r, O& o) {
            // A floorNormal without a word about the constraint asks for it.
            if (r.has("floorNormal") && !r.has("directionalConstraint"))
              o.directionalConstraint = true;
            if (o.contextual && o.contextual->transitionAngle < o.angle)
              ctx.fail(r.at("contextual"), "the transition angle θ₂ (" +
                                               formatOptionValue(double(o.contextual->transitionAngle)) +
                                               ") must not be below the angle θ₁ (" +
                                               formatOptionValue(double(o.angle)) + ")");
          })
          .build();
  return schema;
}

}  // namespace cutaway
