#include "cutters/terrain_opening/terrain_opening.hpp"

#include <regex>

#include "core/name_pattern.hpp"
#include "cutaway/core/error.hpp"

namespace cutaway {

namespace {

// Without layers of its own, the terrain opens above the scene's pipe networks; its patterns
// must name objects.
void completeTerrainOpening(const json_reader::Context& ctx, const std::string& pointer,
                            Scene& scene) {
  TerrainOpeningOptions& o = *scene.cutters.find<TerrainOpeningOptions>();
  if (o.lines.empty())
    for (const PipeNetwork& net : scene.networks)
      for (const Pipe& p : net.pipes) {
        std::vector<glm::vec2> xz;
        for (const glm::vec3& q : p.nodes) xz.emplace_back(q.x, q.z);
        o.lines.push_back(std::move(xz));
      }
  if (o.lines.empty())
    ctx.fail(pointer,
             "no network: give \"network\" layers, \"lines\" or scene \"networks\" (Konev18 §4 "
             "opens the terrain above pipes)");
  for (const auto& [key, pattern] : {std::pair{"terrain", o.terrain}, std::pair{"buildings", o.buildings}}) {
    if (pattern.empty()) {
      if (key == std::string("terrain"))
        ctx.fail(pointer + "/terrain", "required: a pattern naming the terrain objects to open");
      continue;
    }
    const std::regex re = regex(ctx, pattern, pointer + "/" + key);
    if (std::none_of(scene.objects.begin(), scene.objects.end(), [&](const SceneObject& s) {
          return !s.proxy && std::regex_match(s.name, re);
        }))
      ctx.fail(pointer + "/" + key, "no object name matches " + quote(pattern));
  }
}

}  // namespace

CutterType terrainOpeningCutterType() {
  return {.key = "terrainOpening",
          .title = "Terrain opening (Konev18)",
          .glsl = "cutters/terrain_opening/terrain_opening.glsl",
          .name = "terrain",
          .schema = &terrainOpeningSchema(),
          .complete = completeTerrainOpening,
          .create = [](FrameSetup& setup) -> std::unique_ptr<Cutter> {
            return std::make_unique<TerrainOpening>(setup);
          }};
}

TerrainOpening::TerrainOpening(FrameSetup& setup)
    : setup_(setup),
      terrain_(setup.scene.objects.size(), false),
      cutBuildings_(setup.scene.objects.size(), false),
      distanceUnit_(setup.bindings.textureUnit("TERRAIN_DISTANCE")),
      thresholdImage_(setup.bindings.imageUnit("TERRAIN_THRESHOLD")),
      classImage_(setup.bindings.imageUnit("TERRAIN_CLASS")),
      frameLocation_(setup.bindings.uniformLocation("TERRAIN_FRAME")),
      paramsLocation_(setup.bindings.uniformLocation("TERRAIN_PARAMS")),
      wallLocation_(setup.bindings.uniformLocation("TERRAIN_WALL")) {
  const TerrainOpeningOptions& options = this->options();
  const Scene& scene = setup.scene;
  const std::regex terrain = compileNamePattern(options.terrain);
  const std::regex buildings =
      compileNamePattern(options.buildings.empty() ? "$^" : options.buildings);
  Bounds bounds;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& o = scene.objects[i];
    if (o.proxy) continue;
    if (std::regex_match(o.name, terrain)) {
      terrain_[i] = true;
      bounds.extend(o.worldBounds());
    } else if (options.cutBuildings && std::regex_match(o.name, buildings)) {
      cutBuildings_[i] = true;
    }
  }
  // No terrain object (a viewer's scene that just turned the cutter on): nothing to open.
  if (bounds.empty()) bounds.extend(glm::vec3(0.0f)), bounds.extend(glm::vec3(1.0f));
  field_ = terrainField(options, bounds);
  const int n = field_.resolution;
  texture_ = gl::Texture::create2D(GL_R32F, n, n);
  glTextureSubImage2D(texture_.id(), 0, 0, 0, n, n, GL_RED, GL_FLOAT, field_.distance.data());
  threshold_ = setup.frame.declare(
      "terrainThreshold",
      {.format = GL_RG32F,
       .meaning = "Konev18 eq. 1 at the last terrain fragment of the pixel: x = camera distance "
                  "d_c (scene units), y = threshold t, z = 0",
       .aovChannels = 3});
  class_ = setup.frame.declare("terrainClass",
                               {.format = GL_R32UI,
                                .meaning = "Konev18 eqs. 2-3 over the pixel's terrain fragments: "
                                           "0 none, 1 terrain drawn, 2 artificial thickness, 3 a "
                                           "fragment discarded (the largest seen)"});
}

bool TerrainOpening::cuts(std::size_t index) const {
  return (terrain_[index] || cutBuildings_[index]) &&
         setup_.scene.objects[index].mayBeCutBy(TerrainOpeningOptions::kKey);
}

void TerrainOpening::bindForGeometry() const {
  const float zero[4] = {0, 0, 0, 0};
  const GLuint none = 0;
  const Frame& frame = setup_.frame;
  glClearTexImage(frame.texture(threshold_).id(), 0, GL_RG, GL_FLOAT, zero);
  glClearTexImage(frame.texture(class_).id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &none);
  glBindTextureUnit(distanceUnit_, texture_.id());
  glBindImageTexture(thresholdImage_, frame.texture(threshold_).id(), 0, GL_FALSE, 0,
                     GL_WRITE_ONLY, GL_RG32F);
  glBindImageTexture(classImage_, frame.texture(class_).id(), 0, GL_FALSE, 0, GL_READ_WRITE,
                     GL_R32UI);
}

void TerrainOpening::setProgramUniforms(GLuint program) const {
  const TerrainOpeningOptions& o = options();
  glProgramUniform4f(program, frameLocation_, field_.min.x, field_.min.y, 1.0f / field_.size.x,
                     1.0f / field_.size.y);
  glProgramUniform4f(program, paramsLocation_, o.w, o.s, o.cameraDistance ? 1.0f : 0.0f,
                     float(field_.resolution));
  glProgramUniform1f(program, wallLocation_, o.wall);
}

std::string TerrainOpening::glslDefines() const {
  return std::string("#define TERRAIN_NEAREST ") + (field_.nearest ? "1" : "0") + "\n";
}

CutLook TerrainOpening::look(std::size_t) const {
  // Eq. 3's artificial thickness is shown as the cut surface.
  return {.cutSurface = true, .cutColor = options().thicknessColor.value_or(kSoilColor)};
}

std::vector<Aov> TerrainOpening::extraAovs() const {
  const int n = field_.resolution;
  FloatImage image(n, n, 1);
  image.data = field_.distance;
  image.flipVertically();  // rows of increasing z stored first; AOVs run top to bottom
  return {{"terrainDistance",
           std::string("D_p (Konev18 §4): distance from the texel's centre to the closest ") +
               (field_.nearest ? "drawn pipe texel's centre" : "pipe polyline") +
               ", min(texels, 255) / 255, over the terrain's x (columns) and z (rows, "
               "decreasing downwards) extent; sampled " +
               (field_.nearest ? "at the nearest texel" : "bilinearly between texel centres"),
           std::move(image)}};
}

}  // namespace cutaway
