// The clip-surface cutter's options as the scene file, the viewer and the CLI name them.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <utility>

#include "core/json_reader.hpp"
#include "cutaway/cutters/clip_surfaces.hpp"

namespace cutaway {

namespace {

using namespace json_reader;
using O = ClipSurfaceOptions;
using S = ClipSurface;
using Type = OptionSpec::Type;

// An offset map (Trapp13 §4.2): a PNG file, a procedural recipe, or a blend of two maps.
// Blends nest; deeper than this is no offset map anyone means (and would exhaust the stack).
constexpr int kMaxBlendDepth = 32;

FloatImage offsetMap(const Context& ctx, const json& j, const std::string& ptr, int depth = 0) {
  if (depth > kMaxBlendDepth)
    ctx.fail(ptr, "offset-map blends nest deeper than " + std::to_string(kMaxBlendDepth) + " levels");
  if (j.is_string()) {
    const std::filesystem::path file = ctx.baseDir / string(ctx, j, ptr);
    if (!std::filesystem::is_regular_file(file))
      ctx.fail(ptr, "no such offset map: " + file.string());
    try {
      FloatImage map = readPngGray(file);
      map.flipVertically();  // the image's bottom row is t = 0
      return map;
    } catch (const Error& e) {
      ctx.fail(ptr, e.reason() + " (" + file.string() + ")");
    }
  }
  ObjectReader r(ctx, j, ptr);
  if (const json* v = r.take("blend")) {
    static const std::vector<std::string> ops{"add", "multiply", "max", "min", "mix", "screen"};
    const std::string op = oneOf(ctx, *v, r.at("blend"), ops);
    const json& layers = r.require("layers");
    if (!layers.is_array() || layers.size() != 2)
      ctx.fail(r.at("layers"), "expected two offset maps to blend");
    float weight = 0.5f;
    if (const json* w = r.take("weight")) weight = float(number(ctx, *w, r.at("weight"), 0, 1));
    r.finish();
    const auto index = std::size_t(std::find(ops.begin(), ops.end(), op) - ops.begin());
    return blendOffsetMaps(offsetMap(ctx, layers[0], r.at("layers") + "/0", depth + 1),
                           offsetMap(ctx, layers[1], r.at("layers") + "/1", depth + 1),
                           OffsetBlend(index), weight);
  }
  OffsetMapRecipe recipe;
  const std::string pattern =
      oneOf(ctx, r.require("pattern"), r.at("pattern"), {"flat", "sawtooth", "noise", "ridged"});
  recipe.pattern = pattern == "flat"       ? OffsetPattern::Flat
                   : pattern == "sawtooth" ? OffsetPattern::Sawtooth
                   : pattern == "noise"    ? OffsetPattern::Noise
                                           : OffsetPattern::Ridged;
  if (const json* v = r.take("size")) recipe.size = integer(ctx, *v, r.at("size"), 2, 4096);
  if (const json* v = r.take("frequency"))
    recipe.frequency = integer(ctx, *v, r.at("frequency"), 1, 1024);
  if (const json* v = r.take("octaves")) recipe.octaves = integer(ctx, *v, r.at("octaves"), 1, 10);
  if (const json* v = r.take("seed"))
    recipe.seed = unsigned(integer(ctx, *v, r.at("seed"), 0, 1 << 30));
  r.finish();
  return makeOffsetMap(recipe);
}

OptionsSchema surfaceSchema() {
  return OptionsBuilder<S>()
      // The placement is checked as a whole (U ⟂ V, S > 0): the viewer moves it along N and
      // scales its height through the derived values below.
      .vec3("origin", &S::origin, -1e30, 1e30,
            {.doc = "O: a corner of the cap's extent (Trapp13 §4.1).",
             .required = true,
             .fileOnly = true})
      .vec3("u", &S::u, -1e30, 1e30,
            {.doc = "U: the extent's first side; orthogonal to V, N = Û × V̂.",
             .required = true,
             .fileOnly = true})
      .vec3("v", &S::v, -1e30, 1e30,
            {.doc = "V: the extent's second side.", .required = true, .fileOnly = true})
      .vec3("scale", &S::scale, -1e30, 1e30,
            {.doc = "S: offset-map repeats along U and V; S_z: the height in scene units (eq. 1).",
             .fileOnly = true})
      .value("enabled", &S::enabled,
             {.label = "on",
              .doc = "Whether this surface clips (§4.5: each surface can be switched).",
              .live = true})
      .optional("capColor", &S::capColor, Type::Color, 0, 1, glm::vec3(0.5f),
                {.label = "cap colour",
                 .doc = "Colour of this surface's caps; unset: each capped object's colour, "
                        "darker.",
                 .live = true})
      .derived(
          "position", Type::Float, -1e30, 1e30,
          [](const S& cs) -> OptionValue { return double(glm::dot(cs.origin, cs.normal())); },
          [](S& cs, const OptionValue& v) {
            const glm::vec3 n = cs.normal();
            cs.origin += (float(std::get<double>(v)) - glm::dot(cs.origin, n)) * n;
          },
          {.label = "position along N",
           .doc = "Moves the surface along its normal N (scene units: N·O).",
           .live = true})
      .derived(
          "height", Type::Float, 0, 1e30,
          [](const S& cs) -> OptionValue { return double(cs.scale.z); },
          [](S& cs, const OptionValue& v) { cs.scale.z = float(std::get<double>(v)); },
          {.label = "height S_z",
           .doc = "Scale of the offset map along −N, scene units (eq. 1).",
           .live = true})
      // The offset map (a PNG, a recipe or a blend) and the optional diffuse map (§6.1).
      .readHook([](const Context& ctx, ObjectReader& r, S& cs) {
        if (const json* v = r.take("offsetMap"))
          cs.offsetMap = offsetMap(ctx, *v, r.at("offsetMap"));
        if (const json* v = r.take("diffuseMap")) {
          if (!v->is_string()) ctx.fail(r.at("diffuseMap"), "expected a PNG file name");
          const std::filesystem::path file = ctx.baseDir / string(ctx, *v, r.at("diffuseMap"));
          if (!std::filesystem::is_regular_file(file))
            ctx.fail(r.at("diffuseMap"), "no such diffuse map: " + file.string());
          try {
            cs.diffuseMap = readPng(file);
            cs.diffuseMap.flipVertically();  // the image's bottom row is t = 0
          } catch (const Error& e) {
            ctx.fail(r.at("diffuseMap"), e.reason() + " (" + file.string() + ")");
          }
        }
      })
      .check([](const Context& ctx, ObjectReader& r, S& cs) {
        const glm::dvec3 u(cs.u), v(cs.v);
        const double lu = glm::length(u), lv = glm::length(v);
        if (lu <= 0.0 || lv <= 0.0) ctx.fail(r.pointer(), "u and v must not be zero vectors");
        // The shaders square them in 32-bit floats (T of eq. 3): keep the squares normal.
        for (const auto& [key, length] : {std::pair{"u", lu}, std::pair{"v", lv}})
          if (!(length >= 1e-15 && length <= 1e15)) {
            char text[32];
            std::snprintf(text, sizeof text, "%.3g", length);
            ctx.fail(r.at(key), std::string("its length, ") + text +
                                    ", lies outside [1e-15, 1e15] scene units (32-bit floats "
                                    "square it)");
          }
        if (std::abs(glm::dot(u, v)) > 1e-4 * lu * lv)
          ctx.fail(r.at("v"), "u and v must be orthogonal (Trapp13 §4.1)");
        if (r.has("scale") && (cs.scale.x <= 0.0f || cs.scale.y <= 0.0f || cs.scale.z < 0.0f))
          ctx.fail(r.at("scale"), "repeats (x, y) must be > 0 and the height (z) >= 0");
      })
      .build();
}

OptionsSchema capStyleSchema() {
  using C = CapStyle;
  return OptionsBuilder<C>()
      .value("normalMap", &C::normalMap,
             {.label = "cap normal map",
              .doc = "Shade the caps' relief from the offset map's gradients (§6.1).",
              .live = true})
      .number("occlusion", &C::occlusion, 0, 1,
              {.label = "cap occlusion", .doc = "Strength of the occlusion map derived from the offset map.",
               .live = true})
      .value("solidTexture", &C::solidTexture,
             {.label = "solid texture",
              .doc = "Marble-like procedural solid texture on the caps (Fig. 11).", .live = true})
      .number("solidTextureScale", &C::solidTextureScale, 1e-3, 1e4,
              {.label = "solid texture scale", .doc = "Veins per scene-bounds radius.", .live = true,
               .sliderMax = 20})
      .build();
}

}  // namespace

const OptionsSchema& clipSurfacesSchema() {
  static const OptionsSchema schema =
      OptionsBuilder<O>()
          .array("surfaces", &O::surfaces, 1, std::size_t(kMaxClipSurfaces), surfaceSchema(),
                 {.doc = "clip surfaces, evaluated in one pass (Trapp13 §4.5)", .required = true})
          .choice("combine", &O::combine,
                  {{"union", O::Combine::Union}, {"intersection", O::Combine::Intersection}},
                  {.doc = "union: clipped where any enabled surface clips; intersection: where all "
                          "of them do (Trapp13 §4.5).",
                   .live = true})
          .value("caps", &O::caps,
                 {.doc = "Close the cuts of watertight objects with cap surfaces (§5)."})
          .choice("parity", &O::parity,
                  {{"static", O::Parity::Static}, {"perFrame", O::Parity::PerFrame}},
                  {.doc = "Depth sprites built once per mesh, or re-peeled every frame for moving "
                          "objects (§6.3)."})
          .number("depthSpriteResolution", &O::depthSpriteResolution, 16, 4096,
                  {.label = "depth-sprite resolution", .doc = "Texels per side of each sprite layer."})
          .group("capStyle", &O::capStyle, capStyleSchema(), {.doc = "Cap stylization (§6.1)."})
          .build();
  return schema;
}

}  // namespace cutaway
